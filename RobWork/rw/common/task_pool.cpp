#include "rw/common/task_pool.hpp"

#include <algorithm>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rw::common {

TaskPool::TaskPool(int threads, const std::atomic<bool>* stop)
    : threads_(std::max(1, threads)), stop_(stop) {}

std::size_t TaskPool::run(std::size_t count, const Task& task, const WorkerEnd& workerEnd) const {
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::exception_ptr first;
  auto takeTasks = [&](int id) {
    for (;;) {
      if (failed.load() || (stop_ != nullptr && stop_->load())) return;
      const std::size_t i = next.fetch_add(1);
      if (i >= count) return;
      try {
        task(i, id);
        finished.fetch_add(1);
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!first) first = std::current_exception();
        failed.store(true);
      }
    }
  };
  auto worker = [&](int id) {
    takeTasks(id);
    if (workerEnd) workerEnd(id);
  };
  const int workers =
      static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads_), count));
  std::vector<std::thread> others;
  others.reserve(static_cast<std::size_t>(std::max(0, workers - 1)));
  try {
    for (int t = 1; t < workers; ++t) others.emplace_back(worker, t);
  } catch (...) {
    // No thread could be started: the ones running stop after their task.
    failed.store(true);
    for (auto& t : others) t.join();
    throw;
  }
  worker(0);
  for (auto& t : others) t.join();
  if (first) std::rethrow_exception(first);
  return finished.load();
}

}  // namespace rw::common

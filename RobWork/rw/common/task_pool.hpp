#pragma once

#include <atomic>
#include <cstddef>
#include <functional>

namespace rw::common {

/// Runs numbered tasks on a fixed number of worker threads, the calling thread among them: the
/// one pool for all parallel work (the benchmark's scenes, the generator's scenes, the baseline's
/// scenes, the report's pictures).
///
/// Tasks start in their number order. A task keeps its result in a slot the caller owns, indexed
/// by the task's number, so results are in the same order whatever the thread count. When a task
/// throws, no further task starts, the tasks already running finish (their results stay in their
/// slots, written files stay written), and run() rethrows the first exception. A stop flag (set
/// by a signal handler, for instance) ends a run the same way, without an exception.
class TaskPool {
 public:
  /// One task: its number (0 .. count-1) and the worker running it (0 .. threads()-1; 0 is the
  /// calling thread), so that per-worker state (a renderer, a loaded scene) can live in a vector
  /// indexed by worker.
  using Task = std::function<void(std::size_t task, int worker)>;
  /// Called on a worker's own thread once it takes no more tasks (to release per-worker state
  /// that belongs to its thread, such as an OpenGL context); it must not throw.
  using WorkerEnd = std::function<void(int worker)>;

  /// A pool of `threads` workers (values below 1 count as 1). `stop`, if given, is read before
  /// each task starts: once it is true, no further task starts. It must outlive the pool.
  explicit TaskPool(int threads, const std::atomic<bool>* stop = nullptr);

  /// Number of workers.
  int threads() const { return threads_; }

  /// Runs task(i, worker) for i = 0 .. count-1 on min(threads(), count) workers and returns
  /// when every started task has ended (and workerEnd, if given, has run on each worker).
  /// @returns the number of tasks that finished (count unless the stop flag was set).
  /// @throws the first exception a task threw (in time), after the running tasks finished.
  std::size_t run(std::size_t count, const Task& task, const WorkerEnd& workerEnd = {}) const;

 private:
  int threads_;
  const std::atomic<bool>* stop_;
};

}  // namespace rw::common

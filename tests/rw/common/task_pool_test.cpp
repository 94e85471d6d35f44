// rw::common::TaskPool: results land in task order whatever the thread count; tasks start in
// number order; the first exception comes back after the running task finished, and no further
// task starts; a stop flag ends a run without an exception; per-worker clean-up runs on the
// worker's own thread.
#include "rw/common/task_pool.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using rw::common::TaskPool;

// A value that needs some work, so that workers overlap.
long long slowSquare(std::size_t i) {
  long long sum = 0;
  for (std::size_t k = 0; k < 2000 * (i % 7 + 1); ++k) sum += static_cast<long long>(k % 3);
  return static_cast<long long>(i * i) + (sum < 0 ? 1 : 0);
}

TEST(TaskPool, ResultsAreInTaskOrderWhateverTheThreadCount) {
  std::vector<long long> expected(200);
  for (std::size_t i = 0; i < expected.size(); ++i) expected[i] = static_cast<long long>(i * i);
  for (const int threads : {1, 2, 3, 8}) {
    std::vector<long long> slots(expected.size(), -1);
    const TaskPool pool(threads);
    const std::size_t finished =
        pool.run(slots.size(), [&](std::size_t i, int /*worker*/) { slots[i] = slowSquare(i); });
    EXPECT_EQ(finished, slots.size()) << threads << " threads";
    EXPECT_EQ(slots, expected) << threads << " threads";
  }
}

TEST(TaskPool, OneThreadRunsTasksInNumberOrderOnTheCallingThread) {
  std::vector<std::size_t> order;
  std::set<std::thread::id> threads;
  const TaskPool pool(1);
  pool.run(10, [&](std::size_t i, int worker) {
    EXPECT_EQ(worker, 0);
    order.push_back(i);
    threads.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  ASSERT_EQ(threads.size(), 1u);
  EXPECT_EQ(*threads.begin(), std::this_thread::get_id());
}

TEST(TaskPool, ValuesBelowOneMeanOneThreadAndNoTasksIsNothing) {
  EXPECT_EQ(TaskPool(0).threads(), 1);
  EXPECT_EQ(TaskPool(-3).threads(), 1);
  int calls = 0;
  EXPECT_EQ(TaskPool(4).run(0, [&](std::size_t, int) { ++calls; }), 0u);
  EXPECT_EQ(calls, 0);
}

// Task 0 runs until task 1 has thrown; the exception comes back, task 0's result is kept, and
// of the 1000 tasks at most one more (started by the worker of task 0 in the instant before the
// failure was recorded) ever began.
TEST(TaskPool, TheFirstExceptionComesBackAfterTheRunningTaskFinishedAndNoOtherStarts) {
  constexpr std::size_t kCount = 1000;
  std::vector<int> slots(kCount, 0);
  std::vector<std::atomic<bool>> started(kCount);
  std::atomic<bool> thrown{false};
  const TaskPool pool(2);
  try {
    pool.run(kCount, [&](std::size_t i, int /*worker*/) {
      started[i] = true;
      if (i == 0) {
        // Holds its worker until task 1 (on the other worker) has failed, then finishes.
        while (!thrown.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        slots[i] = 100;
        return;
      }
      if (i == 1) {
        thrown = true;
        throw std::runtime_error("task 1 failed");
      }
      slots[i] = static_cast<int>(i);
    });
    FAIL() << "run() returned although a task threw";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "task 1 failed");
  }
  EXPECT_EQ(slots[0], 100) << "the running task was not allowed to finish";
  std::size_t begun = 0;
  for (std::size_t i = 0; i < kCount; ++i) begun += started[i] ? 1 : 0;
  EXPECT_LE(begun, 3u) << "tasks went on starting after the failure";
  for (std::size_t i = 3; i < kCount; ++i) ASSERT_FALSE(started[i]) << "task " << i;
}

// Several tasks fail: exactly one exception comes back, and it is one of theirs.
TEST(TaskPool, OfSeveralFailuresOneComesBack) {
  const TaskPool pool(3);
  std::string message;
  try {
    pool.run(30, [](std::size_t i, int) {
      if (i % 2 == 1) throw std::runtime_error("odd " + std::to_string(i));
    });
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  EXPECT_EQ(message.rfind("odd ", 0), 0u) << message;
}

TEST(TaskPool, AStopFlagEndsTheRunWithoutAnExceptionAndKeepsTheFinishedTasks) {
  std::atomic<bool> stop{false};
  std::vector<int> slots(50, 0);
  const TaskPool pool(1, &stop);
  const std::size_t finished = pool.run(slots.size(), [&](std::size_t i, int) {
    slots[i] = 1;
    if (i == 4) stop = true;
  });
  EXPECT_EQ(finished, 5u);
  EXPECT_EQ(std::vector<int>(slots.begin(), slots.begin() + 5), std::vector<int>(5, 1));
  EXPECT_EQ(std::vector<int>(slots.begin() + 5, slots.end()), std::vector<int>(45, 0));
  // A flag already set starts nothing.
  EXPECT_EQ(pool.run(10, [&](std::size_t, int) { ADD_FAILURE() << "a task started"; }), 0u);
}

TEST(TaskPool, EachWorkersEndRunsOnItsOwnThreadAfterItsTasks) {
  std::mutex mutex;
  std::map<int, std::set<std::thread::id>> taskThreads;
  std::map<int, std::thread::id> endThreads;
  std::map<int, std::size_t> tasksAtEnd;
  std::map<int, std::size_t> tasksRun;
  const TaskPool pool(3);
  pool.run(
      60,
      [&](std::size_t i, int worker) {
        slowSquare(i);
        const std::lock_guard lock(mutex);
        EXPECT_EQ(endThreads.count(worker), 0u) << "a task ran after its worker ended";
        taskThreads[worker].insert(std::this_thread::get_id());
        ++tasksRun[worker];
      },
      [&](int worker) {
        const std::lock_guard lock(mutex);
        EXPECT_EQ(endThreads.count(worker), 0u) << "worker " << worker << " ended twice";
        endThreads[worker] = std::this_thread::get_id();
      });
  EXPECT_EQ(endThreads.size(), 3u);
  EXPECT_EQ(endThreads.at(0), std::this_thread::get_id());
  for (const auto& [worker, ids] : taskThreads) {
    ASSERT_EQ(ids.size(), 1u) << "worker " << worker << " ran on several threads";
    EXPECT_EQ(*ids.begin(), endThreads.at(worker)) << "worker " << worker;
  }
  std::size_t total = 0;
  for (const auto& [worker, n] : tasksRun) total += n;
  EXPECT_EQ(total, 60u);
}

}  // namespace

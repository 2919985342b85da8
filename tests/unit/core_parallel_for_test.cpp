#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/parallel_for.h"

namespace vp {
namespace {

// A sum whose rounding depends on the association order: if chunking changed with the worker
// count, the bits would differ.
double chaoticSum(TaskSystem& tasks, const std::vector<double>& values) {
  return parallelReduce<double>(tasks, static_cast<int64_t>(values.size()), 97, [&](int64_t b, int64_t e) {
    double s = 0.0;
    for (int64_t i = b; i < e; ++i) s += values[static_cast<size_t>(i)];
    return s;
  });
}

std::vector<double> makeValues() {
  std::vector<double> v(100000);
  for (size_t i = 0; i < v.size(); ++i) v[i] = std::sin(double(i) * 0.37) * std::pow(10.0, double(i % 17) - 8.0);
  return v;
}

TEST(ParallelFor, CoversEveryIndexExactlyOnce) {
  for (int workers : {1, 2, 3, 8}) {
    auto tasks = TaskSystem::create(TaskHooks{}, workers);
    std::vector<std::atomic<int>> hits(10007);
    parallelFor(*tasks, 10007, 64, [&](int64_t b, int64_t e) {
      for (int64_t i = b; i < e; ++i) hits[static_cast<size_t>(i)]++;
    });
    for (auto& h : hits) ASSERT_EQ(h.load(), 1) << "workers " << workers;
  }
}

TEST(ParallelFor, ReductionIsBitwiseIdenticalForAnyWorkerCount) {
  const std::vector<double> values = makeValues();
  auto serial = TaskSystem::create(TaskHooks{}, 1);
  const double reference = chaoticSum(*serial, values);
  for (int workers : {2, 3, 4, 7, 16}) {
    auto tasks = TaskSystem::create(TaskHooks{}, workers);
    for (int repeat = 0; repeat < 5; ++repeat) {
      const double s = chaoticSum(*tasks, values);
      ASSERT_EQ(std::memcmp(&s, &reference, sizeof s), 0) << "workers " << workers;
    }
  }
}

// A host task system that runs each enqueued task on fresh threads, split into two halves.
struct HostPool {
  int enqueued = 0;
};

void* enqueueOnThreads(TaskFn task, int32_t count, int32_t minRange, void* taskContext, void* user) {
  static_cast<HostPool*>(user)->enqueued++;
  int32_t mid = count / 2;
  if (mid < minRange) {
    task(0, count, 0, taskContext);
    return nullptr;  // ran inline
  }
  auto* threads = new std::vector<std::thread>();
  threads->emplace_back([=] { task(0, mid, 0, taskContext); });
  threads->emplace_back([=] { task(mid, count, 1, taskContext); });
  return threads;
}

void finishThreads(void* handle, void*) {
  auto* threads = static_cast<std::vector<std::thread>*>(handle);
  for (auto& t : *threads) t.join();
  delete threads;
}

TEST(ParallelFor, HostTaskHooksGiveTheSameResult) {
  const std::vector<double> values = makeValues();
  auto serial = TaskSystem::create(TaskHooks{}, 1);
  const double reference = chaoticSum(*serial, values);
  HostPool pool;
  TaskHooks hooks{&enqueueOnThreads, &finishThreads, &pool};
  auto tasks = TaskSystem::create(hooks, 2);
  const double s = chaoticSum(*tasks, values);
  EXPECT_EQ(std::memcmp(&s, &reference, sizeof s), 0);
  EXPECT_GE(pool.enqueued, 1);
}

// With its workers off (worker_contention.h) the pool runs everything on the caller, and
// the results are bitwise those with them on.
TEST(ParallelFor, WorkersOffRunInlineWithTheSameResult) {
  const std::vector<double> values = makeValues();
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double on = chaoticSum(*tasks, values);
  tasks->setWorkersEnabled(false);
  EXPECT_EQ(tasks->workerCount(), 1);
  std::atomic<int> otherThreads{0};
  const std::thread::id caller = std::this_thread::get_id();
  parallelFor(*tasks, 1000, 1, [&](int64_t, int64_t) { otherThreads += std::this_thread::get_id() != caller; });
  EXPECT_EQ(otherThreads.load(), 0);
  const double off = chaoticSum(*tasks, values);
  EXPECT_EQ(std::memcmp(&on, &off, sizeof on), 0);
  tasks->setWorkersEnabled(true);
  EXPECT_EQ(tasks->workerCount(), 2);
}

// The shared calling-thread system runs every item on the caller, from any thread at once,
// with the pool's chunks and so its bits.
TEST(ParallelFor, TheCallingThreadSystemRunsEverythingOnTheCaller) {
  const std::vector<double> values = makeValues();
  auto pool = TaskSystem::create(TaskHooks{}, 2);
  const double pooled = chaoticSum(*pool, values);
  TaskSystem& inlineTasks = TaskSystem::callingThread();
  EXPECT_EQ(inlineTasks.workerCount(), 1);
  EXPECT_EQ(&inlineTasks, &TaskSystem::callingThread());
  std::atomic<int> elsewhere{0};
  auto run = [&] {
    const std::thread::id caller = std::this_thread::get_id();
    parallelFor(inlineTasks, 1000, 1, [&](int64_t, int64_t) { elsewhere += std::this_thread::get_id() != caller; });
    const double sum = chaoticSum(inlineTasks, values);
    EXPECT_EQ(std::memcmp(&pooled, &sum, sizeof sum), 0);
  };
  std::thread other(run);
  run();
  other.join();
  EXPECT_EQ(elsewhere.load(), 0);
}

#if defined(__linux__)
// The pool's run delay (run_delay.h) is known on Linux and never decreases.
TEST(ParallelFor, ThePoolReportsItsThreadsRunDelay) {
  auto tasks = TaskSystem::create(TaskHooks{}, 3);
  const double before = tasks->workerRunDelayMs();
  ASSERT_GE(before, 0.0);
  const std::vector<double> values = makeValues();
  chaoticSum(*tasks, values);
  EXPECT_GE(tasks->workerRunDelayMs(), before);
  EXPECT_LT(TaskSystem::create(TaskHooks{}, 1)->workerRunDelayMs(), 0.0);  // no workers of its own
}
#endif

TEST(ParallelFor, NestedLoopsRunInline) {
  auto tasks = TaskSystem::create(TaskHooks{}, 4);
  std::atomic<int64_t> total{0};
  parallelFor(*tasks, 16, 1, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i)
      parallelFor(*tasks, 100, 10, [&](int64_t b2, int64_t e2) { total += e2 - b2; });
  });
  EXPECT_EQ(total.load(), 1600);
}

// A block the calling thread runs throws: run() rethrows once the workers' blocks in flight
// have ended, drops the blocks nobody claimed, and the pool runs the next job whole.
TEST(ParallelFor, AnExceptionOnTheCallingThreadEndsTheJobAndThePoolGoesOn) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  struct Job {
    std::atomic<bool> callerFailed{false};
    std::atomic<int> workerBlocks{0};
  } job;
  // Workers hold their first block until the caller has failed, so the caller surely claims one.
  auto task = [](int32_t, int32_t, uint32_t worker, void* p) {
    auto* j = static_cast<Job*>(p);
    if (worker == 0) {
      j->callerFailed = true;
      throw std::runtime_error("block failed");
    }
    while (!j->callerFailed) std::this_thread::yield();
    ++j->workerBlocks;
  };
  EXPECT_THROW(tasks->run(task, 64, 1, &job), std::runtime_error);
  EXPECT_TRUE(job.callerFailed);
  const int afterReturn = job.workerBlocks.load();
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(job.workerBlocks.load(), afterReturn);  // nothing of the failed job runs after run()

  std::vector<std::atomic<int>> hits(5000);
  parallelFor(*tasks, 5000, 7, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) hits[static_cast<size_t>(i)]++;
  });
  for (auto& h : hits) ASSERT_EQ(h.load(), 1);
}

// The caller sleeps for a slow worker's block and wakes when it ends; and many short jobs in a
// row (the solvers' pattern, which the caller's spin covers) each run every index once.
TEST(ParallelFor, EveryJobEndsWithAllItsItemsRunWhetherTheCallerSpinsOrSleeps) {
  auto tasks = TaskSystem::create(TaskHooks{}, 3);
  std::atomic<int> slowDone{0};
  parallelFor(*tasks, 12, 1, [&](int64_t b, int64_t e) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    slowDone += static_cast<int>(e - b);
  });
  EXPECT_EQ(slowDone.load(), 12);
  std::vector<int> counts(64, 0);
  for (int job = 0; job < 20000; ++job) {
    parallelFor(*tasks, 64, 1, [&](int64_t b, int64_t e) {
      for (int64_t i = b; i < e; ++i) ++counts[static_cast<size_t>(i)];
    });
  }
  for (int c : counts) ASSERT_EQ(c, 20000);
}

TEST(ParallelFor, EmptyRangeDoesNothing) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  bool called = false;
  parallelFor(*tasks, 0, 8, [&](int64_t, int64_t) { called = true; });
  EXPECT_FALSE(called);
  EXPECT_EQ(parallelReduce<double>(*tasks, 0, 8, [](int64_t, int64_t) { return 1.0; }), 0.0);
}

}  // namespace
}  // namespace vp

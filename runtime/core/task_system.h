// Where parallel work runs: the host's task system (Box2D-v3-style enqueue/finish hooks) or
// VolPhys' built-in thread pool. Work is described as `itemCount` items; callers make items
// coarse (see parallel_for.h) and item boundaries never depend on the worker count, which is
// what keeps results bitwise identical across worker counts.
#pragma once

#include <cstdint>
#include <memory>

namespace vp {

using TaskFn = void (*)(int32_t start, int32_t end, uint32_t worker, void* taskContext);
using EnqueueTaskFn = void* (*)(TaskFn task, int32_t itemCount, int32_t minRange, void* taskContext,
                                void* userContext);
using FinishTaskFn = void (*)(void* userTask, void* userContext);

struct TaskHooks {
  EnqueueTaskFn enqueue = nullptr;  // both nullptr: built-in pool
  FinishTaskFn finish = nullptr;
  void* userContext = nullptr;
};

class TaskSystem {
 public:
  virtual ~TaskSystem() = default;
  // Runs task over [0, itemCount) and returns when all of it has run.
  virtual void run(TaskFn task, int32_t itemCount, int32_t minRange, void* taskContext) = 0;
  // The workers run() uses now (the calling thread included).
  virtual int workerCount() const = 0;

  // Milliseconds the built-in pool's own threads have waited runnable for a CPU since they
  // started (core/run_delay.h); < 0 where unknown (no statistics, or the host's threads).
  virtual double workerRunDelayMs() const { return -1.0; }
  // Whether run() hands items to the other workers (the default) or runs them all on the
  // calling thread. Results are the same either way: item boundaries never depend on it.
  virtual void setWorkersEnabled(bool) {}

  // workerCount includes the calling thread (1 = everything inline).
  static std::unique_ptr<TaskSystem> create(const TaskHooks& hooks, int workerCount);
  // One shared, stateless task system that runs everything on the calling thread: for loops
  // too small to pay a dispatch to the workers (the same items, so the same results).
  static TaskSystem& callingThread();
};

}  // namespace vp

#include "core/task_system.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace vp {
namespace {

// Set while a thread runs pool work, so nested parallel loops run inline instead of
// waiting on the (busy) pool they are part of.
thread_local bool t_insideTask = false;

class InlineTaskSystem final : public TaskSystem {
 public:
  void run(TaskFn task, int32_t itemCount, int32_t, void* context) override {
    if (itemCount > 0) task(0, itemCount, 0, context);
  }
  int workerCount() const override { return 1; }
};

// The host's task system. The host may run a task inline and return nullptr.
class HostTaskSystem final : public TaskSystem {
 public:
  HostTaskSystem(const TaskHooks& hooks, int workers) : hooks_(hooks), workers_(workers) {}
  void run(TaskFn task, int32_t itemCount, int32_t minRange, void* context) override {
    if (itemCount <= 0) return;
    if (t_insideTask) {
      task(0, itemCount, 0, context);
      return;
    }
    t_insideTask = true;
    void* handle = hooks_.enqueue(task, itemCount, std::max(1, minRange), context, hooks_.userContext);
    if (handle) hooks_.finish(handle, hooks_.userContext);
    t_insideTask = false;
  }
  int workerCount() const override { return workers_; }

 private:
  TaskHooks hooks_;
  int workers_;
};

// A small pool: worker threads sleep on a condition variable and grab blocks of items from
// an atomic counter; the calling thread works too (as worker 0). Hand-written because the
// host-hook path needs the same item semantics, and neither OpenMP nor TBB lets a host
// replace the scheduler per world.
class ThreadPool final : public TaskSystem {
 public:
  explicit ThreadPool(int workers) : workers_(workers) {
    for (int w = 1; w < workers; ++w) threads_.emplace_back([this, w] { workerLoop(static_cast<uint32_t>(w)); });
  }
  ~ThreadPool() override {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }

  void run(TaskFn task, int32_t itemCount, int32_t minRange, void* context) override {
    if (itemCount <= 0) return;
    int32_t block = std::max<int32_t>(std::max(1, minRange), itemCount / (workers_ * 4));
    if (t_insideTask || itemCount <= block) {
      task(0, itemCount, 0, context);
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = task;
      context_ = context;
      itemCount_ = itemCount;
      block_ = block;
      next_.store(0);
      activeWorkers_ = static_cast<int>(threads_.size());
      ++jobSerial_;
    }
    wake_.notify_all();
    t_insideTask = true;
    drain(0);
    t_insideTask = false;
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return activeWorkers_ == 0; });
  }

  int workerCount() const override { return workers_; }

 private:
  void drain(uint32_t worker) {
    for (;;) {
      int32_t start = next_.fetch_add(block_);
      if (start >= itemCount_) return;
      task_(start, std::min(itemCount_, start + block_), worker, context_);
    }
  }

  void workerLoop(uint32_t worker) {
    uint64_t seen = 0;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || jobSerial_ != seen; });
        if (stopping_) return;
        seen = jobSerial_;
      }
      t_insideTask = true;
      drain(worker);
      t_insideTask = false;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (--activeWorkers_ == 0) done_.notify_one();
      }
    }
  }

  int workers_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  bool stopping_ = false;
  uint64_t jobSerial_ = 0;
  int activeWorkers_ = 0;
  TaskFn task_ = nullptr;
  void* context_ = nullptr;
  int32_t itemCount_ = 0;
  int32_t block_ = 1;
  std::atomic<int32_t> next_{0};
};

}  // namespace

std::unique_ptr<TaskSystem> TaskSystem::create(const TaskHooks& hooks, int workerCount) {
  if (hooks.enqueue && hooks.finish) return std::make_unique<HostTaskSystem>(hooks, std::max(1, workerCount));
  if (workerCount <= 1) return std::make_unique<InlineTaskSystem>();
  return std::make_unique<ThreadPool>(workerCount);
}

}  // namespace vp

#include "core/task_system.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/run_delay.h"

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

struct MarkedTask {
  TaskFn task;
  void* context;
  static void run(int32_t start, int32_t end, uint32_t worker, void* self) {
    const auto* m = static_cast<const MarkedTask*>(self);
    const bool outer = t_insideTask;
    t_insideTask = true;
    m->task(start, end, worker, m->context);
    t_insideTask = outer;
  }
};

// The host's task system. The host may run a task inline and return nullptr. Its threads
// are marked as running VolPhys work while they run a task, so work nested in a task (an
// actor running beside another, with its own parallel loops) runs inline there instead of
// calling the host's hooks from a task thread.
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
    MarkedTask marked{task, context};
    void* handle = hooks_.enqueue(&MarkedTask::run, itemCount, std::max(1, minRange), &marked, hooks_.userContext);
    if (handle) hooks_.finish(handle, hooks_.userContext);
    t_insideTask = false;
  }
  int workerCount() const override { return workers_; }

 private:
  TaskHooks hooks_;
  int workers_;
};

// A small pool: the calling thread works too (as worker 0) and the others grab blocks of
// items from an atomic counter. Solver loops dispatch many short jobs (a CG iteration is a
// handful of vector passes), so waking a sleeping thread for each would cost more than the
// job: workers spin briefly on the job counter before they block on a condition variable.
// The caller waits for the job's items, not for the workers: a worker that the OS has not
// run since the job began holds nothing and is not waited for. Hand-written because the
// host-hook path needs the same item semantics, and neither OpenMP nor TBB lets a host
// replace the scheduler per world.
class ThreadPool final : public TaskSystem {
 public:
  // Throws std::system_error when a thread cannot be started, after stopping those that were.
  explicit ThreadPool(int workers) : workers_(workers), delays_(static_cast<size_t>(workers)) {
    try {
      threads_.reserve(static_cast<size_t>(workers - 1));
      for (int w = 1; w < workers; ++w) threads_.emplace_back([this, w] { workerLoop(static_cast<uint32_t>(w)); });
    } catch (...) {
      stop();
      throw;
    }
    // Each worker opens its own statistics first thing; wait for them so reads never race.
    while (started_.load(std::memory_order_acquire) < workers - 1) std::this_thread::yield();
  }
  ~ThreadPool() override { stop(); }

  void run(TaskFn task, int32_t itemCount, int32_t minRange, void* context) override {
    if (itemCount <= 0) return;
    int32_t block = std::max<int32_t>(std::max(1, minRange), itemCount / (workers_ * 4));
    if (t_insideTask || !enabled_ || itemCount <= block) {
      task(0, itemCount, 0, context);
      return;
    }
    openJob(task, itemCount, block, context);
    t_insideTask = true;
    std::exception_ptr failure;
    try {
      drain(0);
    } catch (...) {
      // The blocks no one has claimed are dropped; the workers' blocks in flight still
      // read the job, so it stays open until they end.
      failure = std::current_exception();
      const int32_t unclaimed = itemCount - std::min(itemCount, next_.exchange(itemCount));
      if (unclaimed > 0) finishItems(unclaimed);
    }
    t_insideTask = false;
    waitForItems();
    open_.store(false, std::memory_order_seq_cst);
    if (failure) std::rethrow_exception(failure);
  }

  int workerCount() const override { return enabled_ ? workers_ : 1; }

  double workerRunDelayMs() const override {
    double sum = 0.0;
    for (size_t w = 1; w < delays_.size(); ++w) {
      const double ms = delays_[w].readMs();
      if (ms < 0.0) return -1.0;
      sum += ms;
    }
    return sum;
  }
  void setWorkersEnabled(bool on) override { enabled_ = on; }

 private:
  // About 20-50 microseconds of polling: longer than the gap between a solver's passes,
  // shorter than anything a game frame would notice as burnt time.
  static constexpr int kSpinLimit = 20000;

  // The job's fields change only while no worker is attached (`attached_` is zero) and the
  // job is closed; a worker attaches before it reads them and drains only an open job. The
  // seq_cst pairs (close, then read attached_ / attach, then read open_) mean a worker either
  // sees the job closed or is seen attached.
  void openJob(TaskFn task, int32_t itemCount, int32_t block, void* context) {
    while (attached_.load(std::memory_order_seq_cst) != 0) std::this_thread::yield();
    task_ = task;
    context_ = context;
    itemCount_ = itemCount;
    block_ = block;
    next_.store(0, std::memory_order_relaxed);
    itemsDone_.store(0, std::memory_order_relaxed);
    open_.store(true, std::memory_order_seq_cst);
    {
      // Under the lock so a worker about to sleep cannot miss the new serial.
      std::lock_guard<std::mutex> lock(mutex_);
      jobSerial_.fetch_add(1, std::memory_order_release);
    }
    if (sleepers_.load(std::memory_order_acquire) > 0) wake_.notify_all();
  }

  // Spins briefly, then sleeps until the last block reports. Sleeping matters where the
  // machine has no spare core: a worker preempted inside its block needs the CPU a spinning
  // (or yielding) caller holds, and would wait out the caller's whole time slice for it.
  void waitForItems() {
    for (int spin = 0; spin < kSpinLimit; ++spin)
      if (itemsDone_.load(std::memory_order_acquire) == itemCount_) return;
    std::unique_lock<std::mutex> lock(mutex_);
    callerWaiting_.store(true, std::memory_order_seq_cst);
    itemsFinished_.wait(lock, [&] { return itemsDone_.load(std::memory_order_seq_cst) == itemCount_; });
    callerWaiting_.store(false, std::memory_order_relaxed);
  }

  // Runs blocks until none is left. A block counts as finished even when its task throws.
  void drain(uint32_t worker) {
    for (;;) {
      const int32_t start = next_.fetch_add(block_, std::memory_order_relaxed);
      if (start >= itemCount_) return;
      const int32_t end = std::min(itemCount_, start + block_);
      struct Finished {
        ThreadPool* pool;
        int32_t items;
        ~Finished() { pool->finishItems(items); }
      } finished{this, end - start};
      task_(start, end, worker, context_);
    }
  }

  // The thread that finishes the job's last item wakes a sleeping caller (seq_cst with
  // waitForItems: the caller sees the count complete or this sees the caller waiting).
  void finishItems(int32_t items) {
    if (itemsDone_.fetch_add(items, std::memory_order_seq_cst) + items != itemCount_) return;
    if (!callerWaiting_.load(std::memory_order_seq_cst)) return;
    std::lock_guard<std::mutex> lock(mutex_);
    itemsFinished_.notify_one();
  }

  void workerLoop(uint32_t worker) {
    delays_[worker] = RunDelayReader::forThisThread();
    started_.fetch_add(1, std::memory_order_release);
    uint64_t seen = 0;
    for (;;) {
      int spin = 0;
      while (jobSerial_.load(std::memory_order_acquire) == seen && !stopping_.load(std::memory_order_relaxed) &&
             spin < kSpinLimit)
        ++spin;
      if (jobSerial_.load(std::memory_order_acquire) == seen) {
        std::unique_lock<std::mutex> lock(mutex_);
        sleepers_.fetch_add(1, std::memory_order_acq_rel);
        wake_.wait(lock, [&] { return stopping_.load() || jobSerial_.load(std::memory_order_acquire) != seen; });
        sleepers_.fetch_sub(1, std::memory_order_acq_rel);
      }
      if (stopping_.load()) return;
      seen = jobSerial_.load(std::memory_order_acquire);
      attached_.fetch_add(1, std::memory_order_seq_cst);
      if (open_.load(std::memory_order_seq_cst)) {
        t_insideTask = true;
        drain(worker);
        t_insideTask = false;
      }
      attached_.fetch_sub(1, std::memory_order_release);
    }
  }

  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_.store(true);
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
    threads_.clear();
  }

  int workers_;
  bool enabled_ = true;  // set by the calling thread between runs
  std::vector<RunDelayReader> delays_;  // per worker; [0] (the caller) unused
  std::atomic<int> started_{0};
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_;           // workers sleep here between jobs
  std::condition_variable itemsFinished_;  // the caller sleeps here for a job's last items
  std::atomic<bool> stopping_{false};
  std::atomic<uint64_t> jobSerial_{0};
  std::atomic<int> sleepers_{0};
  std::atomic<bool> callerWaiting_{false};
  std::atomic<bool> open_{false};
  std::atomic<int> attached_{0};
  // The open job.
  TaskFn task_ = nullptr;
  void* context_ = nullptr;
  int32_t itemCount_ = 0;
  int32_t block_ = 1;
  std::atomic<int32_t> next_{0};
  std::atomic<int32_t> itemsDone_{0};
};

}  // namespace

TaskSystem& TaskSystem::callingThread() {
  static InlineTaskSystem inlineTasks;
  return inlineTasks;
}

std::unique_ptr<TaskSystem> TaskSystem::create(const TaskHooks& hooks, int workerCount) {
  if (hooks.enqueue && hooks.finish) return std::make_unique<HostTaskSystem>(hooks, std::max(1, workerCount));
  if (workerCount <= 1) return std::make_unique<InlineTaskSystem>();
  return std::make_unique<ThreadPool>(workerCount);
}

}  // namespace vp

// How long a thread has waited, runnable, for a CPU: the sign that the machine has fewer free
// cores than runnable threads (another process busy, more threads than cores). Read from
// Linux's per-thread scheduler statistics (/proc/thread-self/schedstat, the run delay); where
// they are missing the readers say so and the pool keeps its workers (worker_contention.h).
#pragma once

namespace vp {

// Milliseconds the calling thread has waited runnable since it started; < 0 when unknown.
double threadRunDelayMs();

// A handle on one thread's statistics, opened by that thread, readable from any thread.
class RunDelayReader {
 public:
  // Opens the calling thread's statistics.
  static RunDelayReader forThisThread();
  RunDelayReader() = default;
  RunDelayReader(RunDelayReader&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  RunDelayReader& operator=(RunDelayReader&& other) noexcept;
  RunDelayReader(const RunDelayReader&) = delete;
  RunDelayReader& operator=(const RunDelayReader&) = delete;
  ~RunDelayReader();

  // Milliseconds that thread has waited runnable since it started; < 0 when unknown.
  double readMs() const;

 private:
  int fd_ = -1;
};

}  // namespace vp

// Frame-budget deadlines. Solvers poll a Deadline between iterations and stop with their
// best iterate when it has passed. The clock is injectable: tests use a fake clock that
// advances a fixed amount per query, which makes budget behaviour deterministic.
#pragma once

#include <limits>

namespace vp {

struct Clock {
  using NowFn = double (*)(void* context);  // seconds, monotonic
  NowFn now = nullptr;                      // nullptr: std::chrono::steady_clock
  void* context = nullptr;

  double seconds() const;
};

class Deadline {
 public:
  // A deadline that never expires.
  Deadline() = default;
  // Expires `budgetMs` after now; budgetMs <= 0 means unlimited.
  Deadline(const Clock& clock, double budgetMs);

  bool expired() const;
  double remainingMs() const;
  double elapsedMs() const;
  bool unlimited() const { return end_ == std::numeric_limits<double>::infinity(); }
  // A sub-deadline that ends after `fraction` of what remains (for sharing a budget).
  Deadline share(double fraction) const;
  // After holding back `reserveMs` of what remains for work that comes later: the larger of
  // `fraction` of the rest and all of the rest but laterMs (an equal share, or more when the
  // work after this one is expected to need less).
  Deadline shareLeaving(double fraction, double reserveMs, double laterMs) const;
  // The same, measured from `nowSeconds` (a reading of clock()) so several shares taken at
  // one moment cost one reading.
  Deadline shareLeaving(double fraction, double reserveMs, double laterMs, double nowSeconds) const;
  // This deadline, or `ms` from now when that comes first.
  Deadline within(double ms) const;
  const Clock& clock() const { return clock_; }

 private:
  Clock clock_;
  double start_ = 0.0;
  double end_ = std::numeric_limits<double>::infinity();
};

}  // namespace vp

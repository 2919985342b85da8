#include "core/sliced_job.h"

#include <algorithm>

namespace vp {

// Weight of the newest measurement in a kind's smoothed cost.
constexpr double kSliceCostSmoothing = 0.25;

double SlicedJob::expectedNextMs() const {
  if (queue_.empty()) return 0.0;
  return std::max(costMs_[static_cast<size_t>(queue_.front().kind)], 0.0);
}

double SlicedJob::runNext(const Clock& clock) {
  // Popped before it runs: the slice may queue more behind the rest.
  Slice slice = std::move(queue_.front());
  queue_.pop_front();
  const double start = clock.seconds();
  const bool finished = slice.work();
  const double ms = (clock.seconds() - start) * 1e3;
  ++slicesRun_;
  double& cost = costMs_[static_cast<size_t>(slice.kind)];
  cost = cost < 0.0 ? ms : cost + kSliceCostSmoothing * (ms - cost);
  if (!finished) queue_.push_front(std::move(slice));
  return ms;
}

}  // namespace vp

#include "core/slice_sizer.h"

#include <algorithm>

namespace vp {

namespace {
// No change while the longest slice is within this factor of the target either way (measured
// costs jitter). SliceSizer::kMaxChange bounds a change the other way: one preempted slice
// must not shrink the slabs to nothing.
constexpr double kDeadBand = 1.25;
}  // namespace

SliceSizer::SliceSizer(int64_t preferredSamples)
    : preferred_(std::max<int64_t>(preferredSamples, 1)), samples_(std::min(kMinSamples, preferred_)) {}

void SliceSizer::noteSlice(double ms, double targetMs) {
  longestMs_ = std::max(longestMs_, ms);
  if (targetMs > 0.0 && ms > kDeadBand * targetMs) scale(targetMs / ms);
}

void SliceSizer::adapt(double targetMs) {
  const double longest = longestMs_;
  longestMs_ = 0.0;
  if (targetMs > 0.0 && longest > 0.0 && targetMs > kDeadBand * longest) scale(targetMs / longest);
}

void SliceSizer::scale(double factor) {
  const double scaled = static_cast<double>(samples_) * std::clamp(factor, 1.0 / kMaxChange, kMaxChange);
  samples_ = std::clamp(static_cast<int64_t>(scaled), std::min(kMinSamples, preferred_), preferred_);
}

void SliceSizer::restore(const State& s) {
  samples_ = std::clamp(s.samples, std::min(kMinSamples, preferred_), preferred_);
  longestMs_ = s.longestMs >= 0.0 ? s.longestMs : 0.0;  // NaN too
}

}  // namespace vp

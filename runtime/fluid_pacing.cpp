// Fluid step interval under the frame budget (see fluid_pacing.h).
#include "fluid_pacing.h"

#include <algorithm>

namespace vp {

void FluidPacing::observe(double budgetMs, double otherMs, double fluidMs) {
  otherMs_ = smoothed(otherMs_, otherMs);
  if (budgetMs <= 0.0 || fluidMs <= 0.0) {
    interval_ = 1;
    calmFrames_ = 0;
    return;
  }
  const double room = std::max(budgetMs - otherMs_, 0.0);
  // Smallest interval that fits with kFill of the room; kMaxInterval when none does.
  int needed = 1;
  while (needed < kMaxInterval && fluidMs / needed > kFill * room) ++needed;
  if (needed >= interval_) {
    interval_ = needed;
    calmFrames_ = 0;
    return;
  }
  if (fluidMs / (interval_ - 1) <= kRelaxFill * room) {
    if (++calmFrames_ >= kCalmFrames) {
      --interval_;
      calmFrames_ = 0;
    }
  } else {
    calmFrames_ = 0;
  }
}

}  // namespace vp

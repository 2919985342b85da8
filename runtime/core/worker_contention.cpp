#include "core/worker_contention.h"

#include <algorithm>

namespace vp {

bool WorkerContention::noteFrame(double frameMs, double runDelayMs, bool workersUsed) {
  if (!workersUsed) {
    if (holdLeft_ > 0) --holdLeft_;
    return workersEnabled();
  }
  const bool contended = runDelayMs >= std::max(kMinDelayMs, kContendedFraction * frameMs);
  if (!contended) {
    if (++calm_ >= kCalmFrames) hold_ = kFirstHoldFrames;
    return true;
  }
  calm_ = 0;
  holdLeft_ = hold_;
  hold_ = std::min(2 * hold_, kMaxHoldFrames);
  return false;
}

}  // namespace vp

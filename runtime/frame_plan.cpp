#include "frame_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace vp {

std::vector<int> FramePlan::byPriority(const std::vector<int>& priorities) {
  std::vector<int> order(priorities.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return priorities[a] > priorities[b]; });
  return order;
}

bool FramePlan::due(uint64_t frame, int ordinal, int count, const Deformable& d) {
  const ActorSchedule& s = *d.schedule;
  if (d.pacing == Pacing::EveryFrame) return true;
  if (d.pacing == Pacing::WithLiquids) return d.liquidSteps != s.liquidSteps || s.waitedFrames + 1 >= kMaxInterval;
  const uint64_t k = static_cast<uint64_t>(std::max(s.interval, 1));
  const uint64_t offset = static_cast<uint64_t>(ordinal) * k / static_cast<uint64_t>(std::max(count, 1));
  return s.waitedFrames + 1 >= s.interval || (frame + offset) % k == 0;
}

FramePlan::DeformableDeadlines FramePlan::deformableDeadlines(const Deadline& frame, const ActorSchedule& s,
                                                              double laterFloorsMs, double fluidsMs,
                                                              int remainingDeformables, bool ownRate) {
  DeformableDeadlines d;
  const double fraction = 1.0 / std::max(remainingDeformables, 1);
  // The solve ends early enough for the step's work after it.
  const double tailMs = kMargin * std::max(s.tailMs, 0.0);
  const double now = frame.unlimited() ? 0.0 : frame.clock().seconds();
  d.share = frame.shareLeaving(fraction, fluidsMs + tailMs, laterFloorsMs, now);
  d.forced = s.interval >= kMaxInterval || !ownRate;
  d.floor = d.forced ? Deadline() : frame.shareLeaving(fraction, tailMs, laterFloorsMs, now);
  return d;
}

Deadline FramePlan::fluidShare(const Deadline& frame, const ActorSchedule& s, int equals, bool lowerAfter) {
  const Deadline equal = frame.share(1.0 / std::max(equals, 1));
  if (!lowerAfter || s.expectedMs < 0.0) return equal;
  return equal.within(kMargin * s.expectedMs);
}

int64_t FramePlan::fluidMinWork(const Fluid& f) {
  const int framesAfterThis = f.schedule->stepFrames + 1;
  // At the cap the step ends whatever it costs (it may need more work than expected).
  if (framesAfterThis >= kMaxInterval) return std::numeric_limits<int64_t>::max();
  if (f.expectedWork <= 0) return 0;
  // Paced to end a frame before the cap, so a step that needs more work than expected (more
  // iterations or sub-steps) has a frame to spread it over.
  const int paceFrames = kMaxInterval - 1;
  const double due =
      std::ceil(static_cast<double>(f.expectedWork) * std::min(framesAfterThis, paceFrames) / paceFrames);
  return std::max<int64_t>(0, static_cast<int64_t>(due) - f.workDone);
}

bool FramePlan::adjustIntervals(const std::vector<Deformable>& deformables, const std::vector<bool>& missed,
                                double slackMs) {
  const bool anyMissed = std::find(missed.begin(), missed.end(), true) != missed.end();
  if (anyMissed) {
    // The lowest priority first; among equals the last in slot order.
    int chosen = -1;
    for (int i = 0; i < static_cast<int>(deformables.size()); ++i) {
      const ActorSchedule& s = *deformables[i].schedule;
      if (s.interval >= kMaxInterval || !deformables[i].ownRate()) continue;
      if (chosen < 0 || deformables[i].priority <= deformables[chosen].priority) chosen = i;
    }
    for (const Deformable& d : deformables) d.schedule->calmFrames = 0;
    if (chosen < 0) return false;
    ++deformables[chosen].schedule->interval;
    return true;
  }
  for (const Deformable& d : deformables) {
    ActorSchedule& s = *d.schedule;
    if (s.interval <= 1) continue;
    // One interval lower costs about a step more every interval frames.
    if (s.expectedMs >= 0.0 && slackMs > kMargin * s.expectedMs) {
      if (++s.calmFrames >= kCalmFrames) {
        --s.interval;
        s.calmFrames = 0;
      }
    } else {
      s.calmFrames = 0;
    }
  }
  return true;
}

}  // namespace vp

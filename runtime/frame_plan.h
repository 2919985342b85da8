// The frame plan: which actors advance in a frame, in which order, with what share of the
// frame budget, and at what rate, from each actor's measured costs, accuracy floor and
// priority. The world runs the plan's stages; the plan holds the policy.
//
// The policy, in order of what is protected first:
//   1. Deformables reach their accuracy floor (DeformableDesc targetResidual). A deformable's
//      solve may stop at its share of the frame only once its residual is at or below the
//      floor; above it, it goes on until the frame's end less what the floors of the
//      deformables after it are expected to cost. Deformables run by priority (higher
//      first; equal priorities in slot order).
//   2. When the floors do not fit, deformables lower their rate, never their accuracy: the
//      lowest-priority deformable not yet at kMaxInterval steps every k-th frame with the
//      time it skipped (backward Euler is stable at k dt). The interval comes back down
//      after kCalmFrames frames in which the frame had room for it. Two kinds of deformable
//      keep the rate of what they exchange forces with instead (Pacing): one within reach of
//      a dynamic rigid body steps every frame, as Bullet does; one that a two-way liquid
//      weighs on steps when the liquid completes a step.
//   3. Fluids take what is left, by priority: a fluid is given what one whole step of it is
//      expected to cost, then the next; fluids of equal priority share equally, and time
//      one does not use passes on. A fluid step is resumable (fluid_actor.h): one that does
//      not fit goes on in the next frames, so a fluid short of time lowers its rate (its
//      steps span more frames and simulate their time), never its accuracy. A slice starts
//      only when the share leaves room for its expected cost.
//   4. Rates have a cap: a deformable at kMaxInterval reaches its floor whatever the
//      budget, and a fluid step never spans more than about kMaxInterval frames (each frame
//      of a step must bring it its share of the way). When either overruns the frame, the
//      stats say the budget is infeasible.
// The guarantee: a frame exceeds its budget by at most one slice (one CG iteration or one
// stage of a fluid step) beyond what the estimate of that slice allowed for, except where
// the caps above force work, which the stats flag.
#pragma once

#include <cstdint>
#include <vector>

#include "core/budget_clock.h"

namespace vp {

// What the plan keeps about an actor between frames; each actor owns its own.
struct ActorSchedule {
  int interval = 1;          // deformable: frames per step; fluid: frames its last step spanned
  int waitedFrames = 0;      // deformable: frames since its last step
  int calmFrames = 0;        // deformable: frames in a row with room for a lower interval
  double pendingDt = 0.0;    // simulated time not yet given to a step
  double expectedMs = -1.0;  // smoothed cost of one whole step; < 0 before the first
  double tailMs = -1.0;      // deformable: smoothed cost of what follows its solve (contacts, embedding)
  int stepFrames = 0;        // fluid: frames since its last step completed
  double stepMs = 0.0;       // fluid: what the step in progress has cost so far
  uint64_t liquidSteps = 0;  // deformable paced by liquids: their completed steps at its last step
  int ownRateFrames = 0;     // deformable: frames it keeps its own rate after a step blew up
};

class FramePlan {
 public:
  static constexpr int kMaxInterval = 8;
  static constexpr int kCalmFrames = 30;
  static constexpr double kSmoothing = 0.2;  // weight of the newest cost in the averages
  // The plan expects this multiple of an actor's smoothed cost: costs vary from frame to
  // frame, and the frame's end is what must hold.
  static constexpr double kMargin = 1.25;

  static double smoothed(double average, double sample) {
    return average < 0.0 ? sample : average + kSmoothing * (sample - average);
  }

  // Slab slices are sized (core/slice_sizer.h) to last about this part of the frame budget,
  // so one slice stays well under the budget's quarter that a frame may overrun by.
  static constexpr double kSliceFraction = 1.0 / 8.0;
  static double targetSliceMs(double budgetMs) { return budgetMs > 0.0 ? kSliceFraction * budgetMs : 0.0; }

  // Who sets a deformable's rate. Only Own deformables have their interval raised; the others
  // are at the rate of what they exchange forces with, cannot lower it on their own, and so
  // reach their floor whatever the budget (DeformableDeadlines::forced).
  enum class Pacing {
    Own,  // the plan (policy 2)
    // A two-way liquid weighs on it: it steps when one such liquid completes a step (due), with
    // the time since its last step, so the liquid's load acts over the time it was computed
    // for, as unbudgeted; held over body steps the liquid never saw, the delayed reaction did
    // work on the body (docs/choices.md, "Deformables in fluids").
    WithLiquids,
    // Within reach of a dynamic rigid body: it steps every frame, as Bullet steps the rigid
    // body, and the two solve their contacts together only over the same dt; at a lowered rate
    // the deformable meets it late, deep inside, and its contacts' reactions throw it away
    // (docs/choices.md, "Frame budget"). Wins over WithLiquids.
    EveryFrame,
  };
  // A deformable as the plan sees it this frame.
  struct Deformable {
    int priority = 0;
    ActorSchedule* schedule = nullptr;
    Pacing pacing = Pacing::Own;
    uint64_t liquidSteps = 0;  // WithLiquids: the completed steps of the liquids that weigh on it, summed
    bool ownRate() const { return pacing == Pacing::Own; }
  };
  // A fluid as the plan sees it this frame.
  struct Fluid {
    int priority = 0;
    ActorSchedule* schedule = nullptr;
    int64_t expectedWork = 0;  // of a whole step (core/work_progress.h; 0: unknown)
    int64_t workDone = 0;      // of the step in progress
  };

  // Order of service: indices into the lists by priority (higher first), stable.
  static std::vector<int> byPriority(const std::vector<int>& priorities);

  // Whether a deformable steps this frame (frame, its position in slot order among
  // `count`): deformables at the same interval are staggered over it; one paced by liquids
  // steps when one of them completed a step since its own last step, or at the latest
  // kMaxInterval frames after it (a liquid that has not completed a step yet).
  static bool due(uint64_t frame, int ordinal, int count, const Deformable& d);

  // The two deadlines of a due deformable: `share` (stop there once at the floor) and
  // `floor` (stop there in any case). laterFloorsMs: the expected cost of the due
  // deformables after it; fluidsMs: what the fluids of at least its priority are expected to
  // need this frame; remainingDeformables: itself and those after it; ownRate: as
  // Deformable's (one that is not cannot lower its rate either).
  struct DeformableDeadlines {
    Deadline share, floor;
    // At the interval cap, or at another actor's rate: the floor holds whatever the budget. A
    // solve cut short above it hands a dynamic rigid body it shares the solve with a velocity
    // far from the solution, and leaves a body in a liquid on the floor under forces it has
    // not answered.
    bool forced = false;
  };
  static DeformableDeadlines deformableDeadlines(const Deadline& frame, const ActorSchedule& s,
                                                 double laterFloorsMs, double fluidsMs, int remainingDeformables,
                                                 bool ownRate = true);

  // A fluid's share of what is left of the frame: its expected cost of a whole step when
  // there are fluids of lower priority after it, an equal part among those of its
  // priority otherwise (`equals`: itself and the later fluids of its priority; `lowerAfter`:
  // fluids of lower priority follow).
  static Deadline fluidShare(const Deadline& frame, const ActorSchedule& s, int equals, bool lowerAfter);
  // The work (core/work_progress.h) a fluid must do this frame whatever the budget, so that
  // its step never spans more than about kMaxInterval frames.
  static int64_t fluidMinWork(const Fluid& f);

  // A deformable whose step blew up (and was restored) steps every frame again: the same step at
  // the same length, from the same state, blows up again, and the body stands still. Its
  // interval climbs back as floors are missed, one frame at a time; one paced by liquids keeps
  // its own rate for kCalmFrames frames (its solve did not converge at the liquid's interval).
  static void noteDiverged(ActorSchedule& s) {
    s.interval = 1;
    s.calmFrames = 0;
    s.ownRateFrames = kCalmFrames;
  }

  // After the frame: a deformable that missed its floor raises the interval of the
  // lowest-priority deformable below the cap (`deformables` in slot order; `missed[i]`:
  // the i-th missed its floor); intervals come back down after kCalmFrames frames with
  // `slackMs` (what the frame left unused) above the stepping cost they would add.
  // Returns false when no interval could be raised (all at the cap): the budget cannot
  // hold the floors.
  static bool adjustIntervals(const std::vector<Deformable>& deformables, const std::vector<bool>& missed,
                              double slackMs);
};

}  // namespace vp

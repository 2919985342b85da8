// Times the stages of an actor's step into its stats: each lap adds the time since the last
// one to a phase, with one clock reading (the budget tests count readings).
#pragma once

#include "core/budget_clock.h"
#include "step_stats.h"

namespace vp {

class PhaseTimer {
 public:
  PhaseTimer(const Deadline& clock, ActorStats* stats) : clock_(clock), stats_(stats), mark_(clock.elapsedMs()) {}
  // From now on: what ran since the last lap belongs to no phase of this actor.
  void restart() { mark_ = clock_.elapsedMs(); }
  void lap(Phase phase) {
    const double now = clock_.elapsedMs();
    stats_->phase(phase).ms += now - mark_;
    mark_ = now;
  }

 private:
  const Deadline& clock_;
  ActorStats* stats_;
  double mark_;
};

}  // namespace vp

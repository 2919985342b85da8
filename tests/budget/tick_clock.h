// The budget tests' clock: every reading advances it by one tick, so a budget counts clock
// readings (a CG iteration reads it once, a fluid slice a few times), independent of the
// machine.
#pragma once

#include "core/budget_clock.h"

namespace vp {
namespace testutil {

struct TickClock {
  double seconds = 0.0;
  double tick = 1e-4;  // 0.1 ms
  static double read(void* self) {
    auto* c = static_cast<TickClock*>(self);
    c->seconds += c->tick;
    return c->seconds;
  }
  Clock clock() { return Clock{&TickClock::read, this}; }
};

}  // namespace testutil
}  // namespace vp

// A body spinning and moving through a still viscous liquid, stepped frame by frame: the drag
// may only take its spin and its speed towards zero, never past it (the viscous-traction tests
// of rigid and deformable bodies).
#pragma once

#include <gtest/gtest.h>

#include "world.h"

namespace vp {
namespace testutil {

struct SpinAndSpeed {
  double spin = 0.0, speed = 0.0;
};

// Steps `world` `frames` times (1/60 s); after each, `read()` must give a spin and a speed that
// are not negative and not above the frame before's. Returns the last, or {-1, -1} on a failure.
template <class Read>
SpinAndSpeed stepWhileSpinAndSpeedFall(World& world, int frames, Read read) {
  SpinAndSpeed last = read();
  for (int s = 0; s < frames; ++s) {
    EXPECT_EQ(world.step(1.0 / 60.0), Status::Ok);
    const SpinAndSpeed now = read();
    const bool falls = now.spin >= 0.0 && now.spin <= last.spin && now.speed >= 0.0 && now.speed <= last.speed;
    EXPECT_TRUE(falls) << "frame " << s << ": spin " << last.spin << " -> " << now.spin << ", speed " << last.speed
                       << " -> " << now.speed;
    if (!falls) return SpinAndSpeed{-1.0, -1.0};
    last = now;
  }
  return last;
}

}  // namespace testutil
}  // namespace vp

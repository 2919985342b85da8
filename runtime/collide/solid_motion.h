// A solid's motion as a rigid body's, and how fast it changes: what a fluid's step sees of a
// moving solid (a rigid collider, or a deformable taken as a whole) and what its load's
// stabilization for added mass reads (fluid/solids/solid_motion_history.h).
#pragma once

#include <algorithm>

#include "core/math_types.h"

namespace vp {

// The velocity of the centre of mass and the angular velocity (a deformable's: its angular
// momentum about its centre of mass over its inertia there).
struct SolidMotion {
  Vec3 velocity = Vec3::Zero(), spin = Vec3::Zero();
};

// A drag on a rigid body, linear in its motion: at velocity v and spin w it is
// forceAtRest - linear v (per axis) and torqueAtRest - angular w about its centre of mass (a
// viscous fluid's traction, fluid/solids/viscous_traction.h). The body solves it with its new
// motion (collide/collider.cpp).
struct RigidDrag {
  Vec3 linear = Vec3::Zero();    // N s/m, per axis
  Mat3 angular = Mat3::Zero();   // N m s, symmetric, positive semi-definite
  Vec3 forceAtRest = Vec3::Zero(), torqueAtRest = Vec3::Zero();
  RigidDrag& operator+=(const RigidDrag& o) {
    linear += o.linear;
    angular += o.angular;
    forceAtRest += o.forceAtRest;
    torqueAtRest += o.torqueAtRest;
    return *this;
  }
};

// Rates of change of a SolidMotion (m/s², rad/s²).
struct SolidAcceleration {
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
};

// The added-mass stabilization's cancelling term, limited to what the load shows of the
// reaction it cancels. `expected` is the fluid's reaction to the motion change its step saw
// with its sign turned (added mass times that acceleration); `dynamicLoad` the load less its
// part at rest. The load holds the reaction only where the fluid near the body moved with it
// at the step before, which fails once a fluid step spans frames and the body meets a wall in
// between (the fluid's last field is then far from the body): cancelling a reaction the load
// does not hold pushes the body with a force nothing exerts. So at most the load's component
// against `expected` is cancelled.
inline Vec3 shownReaction(const Vec3& expected, const Vec3& dynamicLoad) {
  const double size = expected.norm();
  if (!(size > 0.0)) return Vec3::Zero();
  const Vec3 direction = expected / size;
  return direction * std::clamp(-dynamicLoad.dot(direction), 0.0, size);
}

}  // namespace vp

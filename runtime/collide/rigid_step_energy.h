// A rigid step's energy for the divergence guard (core/step_energy.h), measured over Bullet's
// sub-steps. The dynamic bodies are measured together: their contacts pass energy from one to
// another, so a body's own energy may rise by any amount while the set's may not. The energy
// is kinetic; the work of a sub-step of h is taken at its end velocities, as Bullet's
// semi-implicit Euler moves the bodies (x' = x + v' h; velocities, not positions, since
// positions far from the origin are too coarse in Bullet's floats for their steps):
//   gravity        Σ m g · v' h, exact;
//   applied loads  the fluids' and the host's forces and torques, · v' h and · ω' h, exact;
//   moving bodies  a kinematic body's contacts put in at most Σ |J| |v_kinematic(p)| (an
//                  inelastic contact's impulse J does no more work on the dynamic body than
//                  on the boundary moving it), a bound;
//   recovery       Bullet pushes a shallow penetration d apart at a bias velocity erp2 |d| / h:
//                  the contact's normal impulse J works at no more than that speed, at most
//                  |J| erp2 |d| / h (which lifts a resting body against gravity); a deep one by
//                  moving positions (split impulse), giving no speed; a bound.
#pragma once

#include <vector>

#include "core/step_energy.h"

class btDiscreteDynamicsWorld;
class btRigidBody;

namespace vp {

class RigidStepEnergy {
 public:
  // At the start of the step: the dynamic bodies' energy and positions.
  void begin(btDiscreteDynamicsWorld& world);
  // Around each of Bullet's sub-steps of h, after the external loads were applied.
  void beforeSubstep();
  void afterSubstep(btDiscreteDynamicsWorld& world, double h);
  // At the end of the step.
  StepEnergy finish() const;
  double totalMass() const { return totalMass_; }

 private:
  struct Body {
    btRigidBody* body;
    double force[3], torque[3];  // the external load of the sub-step
  };
  std::vector<Body> bodies_;
  StepEnergy energy_;
  double totalMass_ = 0.0;
};

}  // namespace vp

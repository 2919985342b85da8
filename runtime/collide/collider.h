// One rigid collider: its exact description (for fluid and deformable queries) and the Bullet
// body that simulates it. Kinematic bodies are driven here, not by Bullet: each sub-step
// advances them by their velocity (or towards the host's target) and hands Bullet the new
// pose through the motion state, from which Bullet derives the velocity its contacts use.
#pragma once

#include <memory>
#include <optional>

#include "collide/bullet_shape_builder.h"
#include "collide/collider_desc.h"
#include "collide/face_coverage.h"
#include "collide/solid_motion.h"
#include "snapshot/actor_states.h"

class btRigidBody;
class btDefaultMotionState;

namespace vp {

class Collider {
 public:
  explicit Collider(ColliderDesc desc);  // desc must be validated
  ~Collider();
  Collider(const Collider&) = delete;
  Collider& operator=(const Collider&) = delete;

  const ColliderDesc& desc() const { return desc_; }
  btRigidBody* body() const { return body_.get(); }
  BodyType bodyType() const { return desc_.bodyType; }

  Pose pose() const;
  void setPose(const Pose& pose);
  Vec3 linearVelocity() const;
  Vec3 angularVelocity() const;
  void setVelocity(const Vec3& linear, const Vec3& angular);
  void setKinematicTarget(const Pose& target);

  // Host control of a dynamic body (the C ABI refuses the other types before calling these).
  // A host load (force, and torque about the body's origin, its centre of mass) acts on every
  // Bullet sub-step of the next world step, then is cleared; loads given before one step add up.
  void addHostLoad(const Vec3& force, const Vec3& torque);
  bool hasHostLoad() const { return !hostForce_.isZero(0.0) || !hostTorque_.isZero(0.0); }
  void clearHostLoad();
  // An impulse changes the velocity at once: dv = J / m, dw = I^-1 L (L about the origin).
  void applyImpulse(const Vec3& linear, const Vec3& angular);
  // What the deformables' contacts and attachments did to a dynamic body in a world step: kept
  // (added up) and spread over the next rigid step as a constant load, as Bullet's own contacts
  // act over each of its sub-steps: a body resting on a jelly then reads no velocity after a
  // step instead of bouncing within it.
  void addContactImpulse(const Vec3& impulse, const Vec3& point);
  bool hasContactLoad() const { return !contactLinear_.isZero(0.0) || !contactMoment_.isZero(0.0); }
  // Once per world step, before its sub-steps: the kept impulses become the load of a step of dt.
  void prepareContactLoad(double dt);
  void clearContactLoad();  // after the step's sub-steps
  Vec3 pendingContactImpulse() const { return contactLinear_; }
  Vec3 pendingContactMoment() const { return contactMoment_; }  // their moment about the world origin
  BodyProperties properties() const { return bodyPropertiesOf(desc_); }
  // A dynamic body's mass and inertia about its centre of mass in the world frame, as Bullet
  // has them now; false when it is not dynamic or its inertia is singular.
  bool massProperties(double* mass, Mat3* inertia) const;
  const CollisionFilter& filter() const { return desc_.filter; }
  // Only through CollisionWorld::setFilter, which gives Bullet the new bits.
  void setFilter(const CollisionFilter& filter) { desc_.filter = filter; }
  void setProperties(const BodyProperties& properties);  // validated; mass rescales the inertia
  // Bullet puts a body that stays slow for a while to sleep; a load, impulse or velocity wakes it.
  bool sleeping() const;
  void setSleeping(bool sleeping);  // asleep: velocities zeroed, as PhysX's putToSleep

  // Exact geometry for deformable contacts and fluid face fractions, at the pose and
  // velocity of the last step; nullptr when the shape has none (an open triangle mesh).
  const PreparedCollider* geometry() const { return geometry_.get(); }
  // The same geometry, kept as it is now for as long as the holder keeps the pointer (a
  // fluid step spanning frames): the collider moves a copy while it is shared.
  std::shared_ptr<const PreparedCollider> sharedGeometry() const { return geometry_; }
  // Brings the geometry to the body's current pose and velocity (after each rigid step).
  void syncGeometry();

  // Loads from the fluids: the dynamic part of a fluid step's (force, torque about the body's
  // origin, the added mass: the fluid that has to accelerate with the body, the change of the
  // body's motion that the step saw, fluid/solids/solid_motion_history.h, and a viscous
  // fluid's drag), and the hydrostatic part at the body's pose now. Applied on every Bullet
  // sub-step of the next world step, then cleared. Dynamic bodies only; others ignore them.
  void addFluidLoad(const Vec3& force, const Vec3& torque, double addedMass, const SolidAcceleration& seen,
                    const RigidDrag& drag);
  void addHydrostaticLoad(const Vec3& force, const Vec3& torque);
  // Once per world step of dt, before its sub-steps and after prepareContactLoad: turns the
  // accumulated load into the force Bullet applies, stabilized for the added mass and the drag
  // (collider.cpp says how).
  void prepareFluidLoad(const Vec3& gravity, double dt);
  // Before each sub-step (Bullet clears forces after each one): the fluid's load and the host's.
  void applyExternalLoads();
  void clearFluidLoad();
  // At the start of every world step: remembers the velocities it starts with.
  void trackVelocity();
  // What the last rigid step changed of the velocities besides the deformables' contact load:
  // now less what trackVelocity kept, less that load's impulse.
  Vec3 lastStepVelocityChange() const;
  Vec3 lastStepSpinChange() const;

  // What evolves (snapshot/actor_states.h): the Bullet body's motion and sleep state, the
  // kinematic driving, pending host loads, the tracked velocities and the geometry's pose.
  // restoreState takes a checked state and cannot fail.
  ColliderState saveState() const;
  void restoreState(const ColliderState& state);

  // Kinematic driving, called by CollisionWorld around Bullet's sub-steps.
  void beginKinematicStep(double dt);          // turns a target into a velocity for this step
  void advanceKinematic(double h, bool last);  // moves by h; on the last sub-step snaps to target
  void endKinematicStep();

 private:
  // The deformables' contact load's torque about the body's centre of mass.
  Vec3 contactTorque() const;
  ColliderDesc desc_;
  BulletShape shape_;
  std::unique_ptr<btDefaultMotionState> motionState_;
  std::unique_ptr<btRigidBody> body_;
  Pose kinematicPose_;
  Vec3 kinematicLinear_ = Vec3::Zero(), kinematicAngular_ = Vec3::Zero();
  std::optional<Pose> target_;
  std::shared_ptr<PreparedCollider> geometry_;
  bool targetActive_ = false;
  Vec3 fluidForce_ = Vec3::Zero(), fluidTorque_ = Vec3::Zero();  // dynamic
  Vec3 hydrostaticForce_ = Vec3::Zero(), hydrostaticTorque_ = Vec3::Zero();
  Vec3 appliedFluidForce_ = Vec3::Zero(), appliedFluidTorque_ = Vec3::Zero();
  double fluidAddedMass_ = 0.0;
  RigidDrag fluidDrag_;
  // The fluid's reactions to the motion changes their steps saw: the sums of added mass times
  // the linear and the angular accelerations.
  Vec3 fluidReaction_ = Vec3::Zero(), fluidSpinReaction_ = Vec3::Zero();
  Vec3 hostForce_ = Vec3::Zero(), hostTorque_ = Vec3::Zero();
  // The contact impulses for the next rigid step: their sum and moment about the world origin.
  Vec3 contactLinear_ = Vec3::Zero(), contactMoment_ = Vec3::Zero();
  // In this one: the load (force, and moment about the origin per second) and, for
  // lastStepVelocityChange, its impulses (the angular one about the centre at the step's start).
  Vec3 contactForce_ = Vec3::Zero(), contactMomentRate_ = Vec3::Zero();
  Vec3 stepContactLinear_ = Vec3::Zero(), stepContactAngular_ = Vec3::Zero();
  Vec3 trackedVelocity_ = Vec3::Zero(), trackedSpin_ = Vec3::Zero();
};

}  // namespace vp

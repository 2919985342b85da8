#include "collide/collider.h"

#include <btBulletDynamicsCommon.h>

#include <Eigen/LU>

#include "collide/bullet_doubles.h"
#include "core/log.h"

namespace vp {
namespace {

btVector3 bt(const Vec3& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }
Vec3 toVec(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

btTransform bt(const Pose& p) {
  return btTransform(btQuaternion(btScalar(p.rotation.x()), btScalar(p.rotation.y()), btScalar(p.rotation.z()),
                                  btScalar(p.rotation.w())),
                     bt(p.position));
}

Pose toPose(const btTransform& t) {
  btQuaternion q = t.getRotation();
  Pose p;
  p.position = toVec(t.getOrigin());
  p.rotation = Quat(q.w(), q.x(), q.y(), q.z());
  return p;
}

static_assert(static_cast<int>(ShapeKind::TriangleMesh) == static_cast<int>(ShapeType::TriangleMesh) &&
                  static_cast<int>(ShapeKind::Plane) == static_cast<int>(ShapeType::Plane),
              "ShapeKind and ShapeType list the shapes in the same order");

ColliderShape exactShapeOf(const ColliderDesc& d) {
  ColliderShape s;
  s.kind = static_cast<ShapeKind>(d.shape.type);  // same order by construction
  s.radius = d.shape.radius;
  s.halfExtents = d.shape.halfExtents;
  s.halfHeight = d.shape.halfHeight;
  s.planeNormal = d.shape.normal;
  s.planeOffset = d.shape.offset;
  if (d.shape.type == ShapeType::ConvexHull) s.hullPoints = d.shape.points;
  if (d.shape.type == ShapeType::TriangleMesh) {
    s.meshVertices = d.shape.points;
    for (const auto& t : d.shape.triangles) s.meshTriangles.emplace_back(t[0], t[1], t[2]);
  }
  s.rotation = d.pose.rotation;
  s.translation = d.pose.position;
  return s;
}

// Rotation by the rotation vector w (axis * angle), exact for constant angular velocity.
Quat exponential(const Vec3& w) {
  double angle = w.norm();
  if (angle < 1e-12) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, w / angle));
}

}  // namespace

Collider::Collider(ColliderDesc desc) : desc_(std::move(desc)), shape_(buildBulletShape(desc_.shape)) {
  const bool dynamic = desc_.bodyType == BodyType::Dynamic;
  const btScalar mass = dynamic ? btScalar(desc_.mass) : btScalar(0);
  btVector3 inertia(0, 0, 0);
  if (dynamic) shape_.shape->calculateLocalInertia(mass, inertia);
  motionState_ = std::make_unique<btDefaultMotionState>(bt(desc_.pose));
  btRigidBody::btRigidBodyConstructionInfo info(mass, motionState_.get(), shape_.shape.get(), inertia);
  info.m_friction = btScalar(desc_.friction);
  info.m_restitution = btScalar(desc_.restitution);
  info.m_linearDamping = btScalar(desc_.linearDamping);
  info.m_angularDamping = btScalar(desc_.angularDamping);
  body_ = std::make_unique<btRigidBody>(info);
  body_->setUserPointer(this);
  kinematicPose_ = desc_.pose;
  // Open meshes (a floor of two triangles) are fine for Bullet but have no inside, so
  // deformables and fluids cannot use them; that is logged, not an error.
  PreparedCollider prepared;
  if (ok(prepareCollider(exactShapeOf(desc_), &prepared)))
    geometry_ = std::make_shared<PreparedCollider>(std::move(prepared));
  else
    log(LogLevel::Warning, "collider '%s' (%s): no exact geometry for deformables and fluids: %s",
        desc_.name.c_str(), shapeTypeName(desc_.shape.type), lastError());
  if (desc_.bodyType == BodyType::Kinematic) {
    body_->setCollisionFlags(body_->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    body_->setActivationState(DISABLE_DEACTIVATION);
    kinematicLinear_ = desc_.linearVelocity;
    kinematicAngular_ = desc_.angularVelocity;
  } else if (dynamic) {
    body_->setLinearVelocity(bt(desc_.linearVelocity));
    body_->setAngularVelocity(bt(desc_.angularVelocity));
    if (desc_.sleeping) setSleeping(true);
  }
}

Collider::~Collider() = default;


void Collider::addFluidLoad(const Vec3& force, const Vec3& torque, double addedMass, const SolidAcceleration& seen,
                            const RigidDrag& drag) {
  if (desc_.bodyType != BodyType::Dynamic) return;
  fluidDrag_ += drag;
  fluidForce_ += force;
  fluidTorque_ += torque;
  fluidAddedMass_ += addedMass;
  fluidReaction_ += addedMass * seen.linear;
  fluidSpinReaction_ += addedMass * seen.angular;
}

void Collider::addHydrostaticLoad(const Vec3& force, const Vec3& torque) {
  if (desc_.bodyType != BodyType::Dynamic) return;
  hydrostaticForce_ += force;
  hydrostaticTorque_ += torque;
}

void Collider::trackVelocity() {
  if (desc_.bodyType != BodyType::Dynamic) return;
  trackedVelocity_ = linearVelocity();
  trackedSpin_ = angularVelocity();
  stepContactLinear_ = stepContactAngular_ = Vec3::Zero();
}

// A liquid's load splits into its hydrostatic part, taken anew at every step from where the
// body is (a fluid step may span several frames under a frame budget, and a buoyancy held
// that long is a delayed spring that pumps the bobbing up), and the dynamic part of the
// fluid's last step, held until the next one.
// That part was computed from a pressure that holds the fluid's reaction to the change of the
// body's motion that the fluid's step saw: F = F_rest - m_a a_seen
// (fluid/solids/solid_motion_history.h). Applied explicitly to a body lighter than its added
// mass m_a, that reaction overshoots every step and the motion blows up (the added-mass
// instability of partitioned coupling). Moving m_a to the left-hand side, with F_o the other
// forces on the body (the host's, the deformables' pushes),
//     (m + m_a) a = m g + F_o + F + m_a a_seen,
// is unconditionally stable for this model and changes nothing at rest (a_seen = 0 and
// F = -m g - F_o give a = 0). Bullet integrates m a = m g + F_o + F_applied, so
//     F_applied = m / (m + m_a) (F + m_a (a_seen - g - F_o / m)),
// with m_a a_seen summed over the fluids and limited to the reaction the dynamic part shows
// (solid_motion.h, shownReaction). Rotation has the same problem (a flat floating box
// rolls itself over without it); its added inertia is taken as the body's own inertia I
// scaled by k = m_a / m, which gives
//     tau_applied = (tau + k I alpha_seen - k tau_o) / (1 + k).
// Except for a sphere: pressure acts along its normals, through its centre, so the pressure
// exerts no torque on it and it has no added inertia (a viscous liquid's traction turns it,
// fluid/solids/viscous_traction.h, and takes no added inertia either). The model would still feed k/(1+k) of
// every spin change back as torque the next step: a spin given by a contact (a paddle's
// friction) came back tripled in all, and a floating ball pushed by a paddle was spun up and
// rolled out of its tank.
// A viscous fluid's drag (RigidDrag: F_0 - D v, tau_0 - D_w w) is solved over the step T
// with the body's other forces, so a light body never overshoots and a steady push meets a
// drag that balances it whatever the mass (docs/choices.md derives it):
//     F_applied = m / (m + m_a + D T) (F + m_a (a_seen - g) + F_0 - D v - D T g - (m_a + D T) F_o / m),
//     ((1 + k) 1 + T D_w I^-1) tau_applied = tau + k I alpha_seen + tau_0 - D_w w - (k 1 + T D_w I^-1) tau_o,
// per axis, I^-1 the world's inverse inertia (a locked axis leaves it singular; the matrix on
// the left stays invertible).
void Collider::prepareFluidLoad(const Vec3& gravity, double dt) {
  if (desc_.bodyType != BodyType::Dynamic) return;
  const double inverseMass = body_->getInvMass();
  if (!(inverseMass > 0.0)) return;
  const double m = 1.0 / inverseMass, ma = fluidAddedMass_;
  const Vec3 reaction = shownReaction(fluidReaction_, fluidForce_);
  const Vec3 pressureForce = fluidForce_ + hydrostaticForce_ + reaction - ma * gravity;
  const bool sphere = desc_.shape.type == ShapeType::Sphere;
  const double k = sphere ? 0.0 : ma / m;
  const Vec3 kAlpha = sphere ? Vec3::Zero() : Vec3(fluidSpinReaction_ / m);
  const btMatrix3x3& invInertia = body_->getInvInertiaTensorWorld();
  // A body with locked rotation has a singular inverse inertia: no stabilization needed there.
  const btVector3 inertiaTimesKAlpha =
      std::abs(invInertia.determinant()) > 0 ? invInertia.inverse() * bt(kAlpha) : btVector3(0, 0, 0);
  const Vec3 spinReaction =
      shownReaction(Vec3(inertiaTimesKAlpha.x(), inertiaTimesKAlpha.y(), inertiaTimesKAlpha.z()), fluidTorque_);
  const Vec3 pressureTorque = fluidTorque_ + hydrostaticTorque_ + spinReaction;
  const RigidDrag& drag = fluidDrag_;
  const Vec3 otherForce = hostForce_ + contactForce_;
  const Vec3 otherTorque = hostTorque_ + contactTorque();
  const Vec3 velocity = linearVelocity();
  for (int a = 0; a < 3; ++a) {
    const double dragT = drag.linear[a] * dt;
    appliedFluidForce_[a] = m / (m + ma + dragT) *
                            (pressureForce[a] + drag.forceAtRest[a] - drag.linear[a] * velocity[a] -
                             dragT * gravity[a] - (ma + dragT) * otherForce[a] / m);
  }
  Mat3 inverseInertia;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) inverseInertia(r, c) = invInertia[r][c];
  const Mat3 dragTOverInertia = dt * drag.angular * inverseInertia;
  const Mat3 resisted = (1.0 + k) * Mat3::Identity() + dragTOverInertia;
  appliedFluidTorque_ = resisted.partialPivLu().solve(pressureTorque + drag.torqueAtRest -
                                                      drag.angular * angularVelocity() -
                                                      (k * Mat3::Identity() + dragTOverInertia) * otherTorque);
}

void Collider::applyExternalLoads() {
  if (desc_.bodyType != BodyType::Dynamic) return;
  body_->activate(true);
  body_->applyCentralForce(bt(appliedFluidForce_ + hostForce_ + contactForce_));
  body_->applyTorque(bt(appliedFluidTorque_ + hostTorque_ + contactTorque()));
}

// The contact load acts where the contacts were, not at the moving body's point: its moment
// about the origin, the deformables' reactions' one, is then the same in every sub-step.
Vec3 Collider::contactTorque() const { return contactMomentRate_ - pose().position.cross(contactForce_); }

void Collider::addHostLoad(const Vec3& force, const Vec3& torque) {
  if (desc_.bodyType != BodyType::Dynamic) return;
  hostForce_ += force;
  hostTorque_ += torque;
  body_->activate(true);
}

void Collider::clearHostLoad() {
  hostForce_ = hostTorque_ = Vec3::Zero();
}

bool Collider::massProperties(double* mass, Mat3* inertia) const {
  const double inverseMass = body_->getInvMass();
  const btMatrix3x3& invInertia = body_->getInvInertiaTensorWorld();
  if (desc_.bodyType != BodyType::Dynamic || !(inverseMass > 0.0) || !(std::abs(invInertia.determinant()) > 0.0))
    return false;
  const btMatrix3x3 I = invInertia.inverse();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) (*inertia)(r, c) = I[r][c];
  *mass = 1.0 / inverseMass;
  return true;
}

void Collider::applyImpulse(const Vec3& linear, const Vec3& angular) {
  if (desc_.bodyType != BodyType::Dynamic) return;
  body_->applyCentralImpulse(bt(linear));
  body_->applyTorqueImpulse(bt(angular));
  body_->activate(true);
}

void Collider::addContactImpulse(const Vec3& impulse, const Vec3& point) {
  if (desc_.bodyType != BodyType::Dynamic) return;
  contactLinear_ += impulse;
  contactMoment_ += point.cross(impulse);
}

void Collider::prepareContactLoad(double dt) {
  stepContactLinear_ = contactLinear_;
  stepContactAngular_ = contactMoment_ - pose().position.cross(contactLinear_);
  contactForce_ = contactLinear_ / dt;
  contactMomentRate_ = contactMoment_ / dt;
  contactLinear_ = contactMoment_ = Vec3::Zero();
}

void Collider::clearContactLoad() { contactForce_ = contactMomentRate_ = Vec3::Zero(); }

Vec3 Collider::lastStepVelocityChange() const {
  const double inverseMass = body_->getInvMass();
  return linearVelocity() - trackedVelocity_ - inverseMass * stepContactLinear_;
}

Vec3 Collider::lastStepSpinChange() const {
  const btVector3 spin = body_->getInvInertiaTensorWorld() * bt(stepContactAngular_);
  return angularVelocity() - trackedSpin_ - Vec3(spin.x(), spin.y(), spin.z());
}

void Collider::setProperties(const BodyProperties& p) {
  if (desc_.bodyType == BodyType::Dynamic && p.mass != desc_.mass) {
    btVector3 inertia(0, 0, 0);
    shape_.shape->calculateLocalInertia(btScalar(p.mass), inertia);
    body_->setMassProps(btScalar(p.mass), inertia);
    body_->updateInertiaTensor();
    body_->activate(true);
  }
  body_->setFriction(btScalar(p.friction));
  body_->setRestitution(btScalar(p.restitution));
  body_->setDamping(btScalar(p.linearDamping), btScalar(p.angularDamping));
  desc_.mass = p.mass;
  desc_.friction = p.friction;
  desc_.restitution = p.restitution;
  desc_.linearDamping = p.linearDamping;
  desc_.angularDamping = p.angularDamping;
}

bool Collider::sleeping() const {
  return desc_.bodyType == BodyType::Dynamic && body_->getActivationState() == ISLAND_SLEEPING;
}

void Collider::setSleeping(bool asleep) {
  if (desc_.bodyType != BodyType::Dynamic) return;
  if (!asleep) {
    body_->activate(true);
    return;
  }
  body_->setLinearVelocity(btVector3(0, 0, 0));
  body_->setAngularVelocity(btVector3(0, 0, 0));
  body_->setActivationState(ISLAND_SLEEPING);
}

void Collider::clearFluidLoad() {
  fluidForce_ = fluidTorque_ = appliedFluidForce_ = appliedFluidTorque_ = Vec3::Zero();
  hydrostaticForce_ = hydrostaticTorque_ = Vec3::Zero();
  fluidReaction_ = fluidSpinReaction_ = Vec3::Zero();
  fluidAddedMass_ = 0.0;
  fluidDrag_ = RigidDrag{};
}

void Collider::syncGeometry() {
  if (!geometry_) return;
  const Pose p = pose();
  const Vec3 linear = linearVelocity(), angular = angularVelocity();
  const ColliderShape& now = geometry_->shape;
  const bool moves = desc_.bodyType != BodyType::Static &&
                     (now.translation != p.position || now.rotation.coeffs() != p.rotation.coeffs());
  if (!moves && now.linearVelocity == linear && now.angularVelocity == angular) return;
  if (geometry_.use_count() > 1) geometry_ = std::make_shared<PreparedCollider>(*geometry_);
  if (moves) setColliderPose(geometry_.get(), p.rotation, p.position);
  geometry_->shape.linearVelocity = linear;
  geometry_->shape.angularVelocity = angular;
}

Pose Collider::pose() const {
  if (desc_.bodyType == BodyType::Kinematic) return kinematicPose_;
  return toPose(body_->getWorldTransform());
}

void Collider::setPose(const Pose& pose) {
  const btTransform t = bt(pose);
  body_->setWorldTransform(t);
  body_->setInterpolationWorldTransform(t);
  motionState_->setWorldTransform(t);
  kinematicPose_ = pose;
  target_.reset();
  targetActive_ = false;
  if (desc_.bodyType == BodyType::Dynamic) body_->activate(true);
}

Vec3 Collider::linearVelocity() const {
  if (desc_.bodyType == BodyType::Kinematic) return kinematicLinear_;
  return toVec(body_->getLinearVelocity());
}

Vec3 Collider::angularVelocity() const {
  if (desc_.bodyType == BodyType::Kinematic) return kinematicAngular_;
  return toVec(body_->getAngularVelocity());
}

void Collider::setVelocity(const Vec3& linear, const Vec3& angular) {
  if (desc_.bodyType == BodyType::Kinematic) {
    kinematicLinear_ = linear;
    kinematicAngular_ = angular;
    target_.reset();
    targetActive_ = false;
    return;
  }
  body_->setLinearVelocity(bt(linear));
  body_->setAngularVelocity(bt(angular));
  body_->activate(true);
}

void Collider::setKinematicTarget(const Pose& target) { target_ = target; }

void Collider::beginKinematicStep(double dt) {
  if (!target_) {
    // A target reached last step leaves the body at rest until the host moves it again.
    if (targetActive_) kinematicLinear_.setZero(), kinematicAngular_.setZero();
    targetActive_ = false;
    return;
  }
  targetActive_ = true;
  kinematicLinear_ = (target_->position - kinematicPose_.position) / dt;
  Quat delta = target_->rotation * kinematicPose_.rotation.conjugate();
  if (delta.w() < 0) delta.coeffs() = -delta.coeffs();  // shortest arc
  Eigen::AngleAxisd aa(delta);
  kinematicAngular_ = aa.axis() * (aa.angle() / dt);
}

void Collider::advanceKinematic(double h, bool last) {
  if (last && targetActive_) {
    kinematicPose_ = *target_;  // no drift from summing sub-steps
  } else {
    kinematicPose_.position += kinematicLinear_ * h;
    kinematicPose_.rotation = (exponential(kinematicAngular_ * h) * kinematicPose_.rotation).normalized();
  }
  motionState_->setWorldTransform(bt(kinematicPose_));
}

void Collider::endKinematicStep() {
  // Keep the step's velocity readable (fluids and deformables use it after the rigid phase);
  // beginKinematicStep clears it next step if no new target came.
  target_.reset();
}


ColliderState Collider::saveState() const {
  ColliderState s;
  RigidBodyState& b = s.body;
  toDoubles(body_->getWorldTransform(), b.transform);
  toDoubles(body_->getInterpolationWorldTransform(), b.interpolationTransform);
  toDoubles(motionState_->m_graphicsWorldTrans, b.motionStateTransform);
  toDoubles(body_->getLinearVelocity(), b.linear);
  toDoubles(body_->getAngularVelocity(), b.angular);
  toDoubles(body_->getInterpolationLinearVelocity(), b.interpolationLinear);
  toDoubles(body_->getInterpolationAngularVelocity(), b.interpolationAngular);
  toDoubles(body_->getTotalForce(), b.totalForce);
  toDoubles(body_->getTotalTorque(), b.totalTorque);
  b.activationState = body_->getActivationState();
  b.deactivationTime = body_->getDeactivationTime();
  b.hitFraction = body_->getHitFraction();
  s.kinematicPose = kinematicPose_;
  s.kinematicLinear = kinematicLinear_;
  s.kinematicAngular = kinematicAngular_;
  s.target = target_;
  s.targetActive = targetActive_;
  s.hostForce = hostForce_;
  s.hostTorque = hostTorque_;
  s.contactLinear = contactLinear_;
  s.contactMoment = contactMoment_;
  s.trackedVelocity = trackedVelocity_;
  s.trackedSpin = trackedSpin_;
  s.hasGeometry = geometry_ != nullptr;
  if (geometry_) {
    const ColliderShape& g = geometry_->shape;
    s.geometryRotation = g.rotation;
    s.geometryTranslation = g.translation;
    s.geometryLinear = g.linearVelocity;
    s.geometryAngular = g.angularVelocity;
  }
  return s;
}

void Collider::restoreState(const ColliderState& s) {
  const RigidBodyState& b = s.body;
  body_->setWorldTransform(btTransformFrom(b.transform));
  body_->setInterpolationWorldTransform(btTransformFrom(b.interpolationTransform));
  motionState_->m_graphicsWorldTrans = btTransformFrom(b.motionStateTransform);
  body_->setLinearVelocity(btVectorFrom(b.linear));
  body_->setAngularVelocity(btVectorFrom(b.angular));
  body_->setInterpolationLinearVelocity(btVectorFrom(b.interpolationLinear));
  body_->setInterpolationAngularVelocity(btVectorFrom(b.interpolationAngular));
  // Bullet clears its forces after every sub-step; a state holds them for completeness.
  body_->clearForces();
  body_->applyCentralForce(btVectorFrom(b.totalForce));
  body_->applyTorque(btVectorFrom(b.totalTorque));
  body_->updateInertiaTensor();
  body_->forceActivationState(b.activationState);
  body_->setDeactivationTime(btScalar(b.deactivationTime));
  body_->setHitFraction(btScalar(b.hitFraction));
  kinematicPose_ = s.kinematicPose;
  kinematicLinear_ = s.kinematicLinear;
  kinematicAngular_ = s.kinematicAngular;
  target_ = s.target;
  targetActive_ = s.targetActive;
  hostForce_ = s.hostForce;
  hostTorque_ = s.hostTorque;
  contactLinear_ = s.contactLinear;
  contactMoment_ = s.contactMoment;
  trackedVelocity_ = s.trackedVelocity;
  trackedSpin_ = s.trackedSpin;
  clearFluidLoad();
  if (geometry_ && s.hasGeometry) {
    const ColliderShape& g = geometry_->shape;
    const bool samePose = g.rotation.coeffs() == s.geometryRotation.coeffs() && g.translation == s.geometryTranslation;
    if (samePose && g.linearVelocity == s.geometryLinear && g.angularVelocity == s.geometryAngular) return;
    // A fluid step in progress may hold the geometry as it is (see sharedGeometry).
    if (geometry_.use_count() > 1) geometry_ = std::make_shared<PreparedCollider>(*geometry_);
    // Moving a mesh rebuilds its tree: not when the pose is the one it has (a save's rebuild).
    if (!samePose) restoreColliderPose(geometry_.get(), s.geometryRotation, s.geometryTranslation);
    geometry_->shape.linearVelocity = s.geometryLinear;
    geometry_->shape.angularVelocity = s.geometryAngular;
  }
}

}  // namespace vp

#include "snapshot/actor_state_io.h"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "deform/deformable_body.h"
#include "fluid/fluid_actor.h"

namespace vp {

namespace {

void writeVec(StateWriter& out, const Vec3& v) { out.doubles(v.data(), 3); }
void writeQuat(StateWriter& out, const Quat& q) { out.doubles(q.coeffs().data(), 4); }
void writePose(StateWriter& out, const Pose& p) {
  writeVec(out, p.position);
  writeQuat(out, p.rotation);
}

Vec3 readVec(StateReader& in, const char* what) {
  Vec3 v;
  in.doubles(v.data(), 3);
  in.requireFinite(what, v.data(), 3);
  return v;
}
Quat readQuat(StateReader& in, const char* what) {
  Quat q;
  in.doubles(q.coeffs().data(), 4);
  in.requireFinite(what, q.coeffs().data(), 4);
  if (in.ok() && !(std::abs(q.norm() - 1.0) < 1e-3)) in.outOfRange(what);
  return q;
}
Pose readPose(StateReader& in, const char* what) {
  Pose p;
  p.position = readVec(in, what);
  p.rotation = readQuat(in, what);
  return p;
}

template <class A>
void readFiniteArray(StateReader& in, A* a, uint64_t expected, const char* what) {
  in.array(a, expected, what);
  in.requireFinite(what, a->data(), a->size());
}

// Field by field: the struct has padding, which must not reach the buffer.
void writeSchedule(StateWriter& out, const ActorSchedule& s) {
  for (int v : {s.interval, s.waitedFrames, s.calmFrames, s.stepFrames, s.ownRateFrames})
    out.value(static_cast<int32_t>(v));
  for (double v : {s.pendingDt, s.expectedMs, s.tailMs, s.stepMs}) out.value(v);
  out.value(s.liquidSteps);
}
void readSchedule(StateReader& in, ActorSchedule* s) {
  for (int* v : {&s->interval, &s->waitedFrames, &s->calmFrames, &s->stepFrames, &s->ownRateFrames})
    *v = in.value<int32_t>();
  for (double* v : {&s->pendingDt, &s->expectedMs, &s->tailMs, &s->stepMs}) *v = in.value<double>();
  s->liquidSteps = in.value<uint64_t>();
  const double values[] = {s->pendingDt, s->expectedMs, s->tailMs, s->stepMs};
  in.requireFinite("a schedule", values, 4);
  if (in.ok() && (s->interval < 1 || s->waitedFrames < 0 || s->calmFrames < 0 || s->stepFrames < 0 ||
                  s->ownRateFrames < 0 || s->pendingDt < 0.0))
    in.outOfRange("a schedule's counts");
}

}  // namespace

void writeColliderState(StateWriter& out, const ColliderState& s) {
  out.value(s.body);
  writePose(out, s.kinematicPose);
  writeVec(out, s.kinematicLinear);
  writeVec(out, s.kinematicAngular);
  out.value(static_cast<uint8_t>(s.target.has_value()));
  if (s.target) writePose(out, *s.target);
  out.value(static_cast<uint8_t>(s.targetActive));
  for (const Vec3* v : {&s.hostForce, &s.hostTorque, &s.contactLinear, &s.contactMoment, &s.trackedVelocity,
                        &s.trackedSpin})
    writeVec(out, *v);
  out.value(static_cast<uint8_t>(s.hasGeometry));
  if (s.hasGeometry) {
    writeQuat(out, s.geometryRotation);
    writeVec(out, s.geometryTranslation);
    writeVec(out, s.geometryLinear);
    writeVec(out, s.geometryAngular);
  }
}

void readColliderState(StateReader& in, bool hasGeometry, ColliderState* s) {
  s->body = in.value<RigidBodyState>();
  const RigidBodyState& b = s->body;
  for (const double* t : {b.transform, b.interpolationTransform, b.motionStateTransform})
    in.requireFinite("a rigid body's transform", t, 12);
  for (const double* v : {b.linear, b.angular, b.interpolationLinear, b.interpolationAngular, b.totalForce,
                          b.totalTorque})
    in.requireFinite("a rigid body's velocity or force", v, 3);
  const double times[] = {b.deactivationTime, b.hitFraction};
  in.requireFinite("a rigid body's sleep timer", times, 2);
  // Bullet's activation states are 1 (active) to 5 (simulation disabled).
  if (in.ok() && (b.activationState < 1 || b.activationState > 5)) in.outOfRange("a rigid body's activation state");
  s->kinematicPose = readPose(in, "a kinematic pose");
  s->kinematicLinear = readVec(in, "a kinematic velocity");
  s->kinematicAngular = readVec(in, "a kinematic velocity");
  if (in.value<uint8_t>() != 0) s->target = readPose(in, "a kinematic target");
  s->targetActive = in.value<uint8_t>() != 0;
  for (Vec3* v : {&s->hostForce, &s->hostTorque, &s->contactLinear, &s->contactMoment, &s->trackedVelocity,
                  &s->trackedSpin})
    *v = readVec(in, "a rigid body's load or velocity");
  s->hasGeometry = in.value<uint8_t>() != 0;
  in.expect("collider's exact geometry (0 or 1)", s->hasGeometry, hasGeometry);
  if (s->hasGeometry && in.ok()) {
    s->geometryRotation = readQuat(in, "a collider's geometry pose");
    s->geometryTranslation = readVec(in, "a collider's geometry pose");
    s->geometryLinear = readVec(in, "a collider's geometry velocity");
    s->geometryAngular = readVec(in, "a collider's geometry velocity");
  }
}

namespace {

// Vec3 arrays as their doubles, three per element.
void writeVecs(StateWriter& out, const Array<Vec3>& a) {
  out.value(static_cast<uint64_t>(a.size()));
  if (!a.empty()) out.doubles(a.data()->data(), 3 * a.size());
}

// `n` vectors, bounded by the buffer and finite.
void readVecElements(StateReader& in, Array<Vec3>* a, uint64_t n, const char* what) {
  if (!in.ok() || !in.has(n, 3 * sizeof(double))) return;
  a->resize(static_cast<size_t>(n));
  if (n > 0) {
    in.doubles(a->data()->data(), 3 * a->size());
    in.requireFinite(what, a->data()->data(), 3 * a->size());
  }
}

void readVecs(StateReader& in, Array<Vec3>* a, uint64_t expected, const char* what) {
  const uint64_t n = in.value<uint64_t>();
  in.expect(what, n, expected);
  readVecElements(in, a, n, what);
}

// A count the reader cannot check (bounded by the buffer only), then the vectors.
void readVecsOfAnyCount(StateReader& in, Array<Vec3>* a, const char* what) {
  readVecElements(in, a, in.value<uint64_t>(), what);
}

// A fluid load's vertex drag (fluid/solids/surface_pressure_load.h): none, or one per vertex of
// the load's forces; coefficients that are not negative, and as many forces at rest.
void readVecDrag(StateReader& in, size_t vertices, VertexDrag* drag) {
  readVecsOfAnyCount(in, &drag->coefficient, "a fluid load's vertex drag");
  if (!drag->coefficient.empty()) in.expect("a fluid load's vertex drag count", drag->coefficient.size(), vertices);
  readVecs(in, &drag->atRest, drag->coefficient.size(), "a fluid load's vertex drag at rest");
  for (const Vec3& c : drag->coefficient)
    if (in.ok() && (c.array() < 0.0).any()) in.outOfRange("a fluid load's vertex drag");
}

// A fluid load's drag on a rigid body (collide/solid_motion.h): per-axis coefficients that are
// not negative, a symmetric positive semi-definite angular one (to round-off).
void writeRigidDrag(StateWriter& out, const RigidDrag& d) {
  writeVec(out, d.linear);
  out.doubles(d.angular.data(), 9);
  writeVec(out, d.forceAtRest);
  writeVec(out, d.torqueAtRest);
}

RigidDrag readRigidDrag(StateReader& in) {
  RigidDrag d;
  d.linear = readVec(in, "a fluid load's rigid drag");
  in.doubles(d.angular.data(), 9);
  in.requireFinite("a fluid load's rigid drag", d.angular.data(), 9);
  d.forceAtRest = readVec(in, "a fluid load's rigid drag");
  d.torqueAtRest = readVec(in, "a fluid load's rigid drag");
  if (!in.ok()) return d;
  const double tolerance = 1e-12 * d.angular.cwiseAbs().maxCoeff();
  const bool semiDefinite = (d.angular - d.angular.transpose()).cwiseAbs().maxCoeff() <= tolerance &&
                            Eigen::SelfAdjointEigenSolver<Mat3>(d.angular).eigenvalues().minCoeff() >= -tolerance;
  if ((d.linear.array() < 0.0).any() || !semiDefinite) in.outOfRange("a fluid load's rigid drag");
  return d;
}

// Arrays a step sizes on first use: empty, or of their full size.
template <class A>
void readEmptyOrFull(StateReader& in, A* a, uint64_t full, const char* what) {
  in.arrayUpTo(a, full, what);
  if (in.ok() && !a->empty() && a->size() != full) in.expect(what, a->size(), full);
}

// A pair contact's friction state (deform/pair_contacts.h), and its size in the stream.
constexpr uint64_t kPairFrictionBytes = 4 * sizeof(double) + 2 * sizeof(uint32_t) + 2 * sizeof(uint8_t);

void writePairFriction(StateWriter& out, const PairFriction& f) {
  writeVec(out, f.stick);
  out.value(f.lastNormalImpulse);
  out.value(f.other.index1);
  out.value(f.other.generation);
  out.value(f.other.rigid);
  out.value(f.sliding);
}

void readPairFriction(StateReader& in, PairFriction* f) {
  f->stick = readVec(in, "a deformable's pair contact stick force");
  f->lastNormalImpulse = in.value<double>();
  in.requireFinite("a deformable's pair contact impulse", &f->lastNormalImpulse, 1);
  f->other.index1 = in.value<uint32_t>();
  f->other.generation = in.value<uint32_t>();
  f->other.rigid = in.value<uint8_t>();
  f->sliding = in.value<uint8_t>();
  if (in.ok() && (f->sliding > 1 || f->other.rigid > 1)) in.outOfRange("a deformable's pair contact state");
}

}  // namespace

void writeDeformableState(StateWriter& out, const DeformableState& s) {
  for (const Array<double>* a : {&s.x, &s.v, &s.externalForce, &s.rotations, &s.lastNormalImpulse}) out.array(*a);
  out.array(s.sliding);
  out.value(static_cast<uint64_t>(s.contacts.size()));
  for (const NodeContact& c : s.contacts) {
    out.value(c.node);
    writeVec(out, c.normal);
    writeVec(out, c.colliderVelocity);
    out.value(c.normalSpeed);
    out.value(c.friction);
    out.value(c.colliderIndex1);
    out.value(c.colliderGeneration);
  }
  writeVecs(out, s.renderPositions);
  writeVecs(out, s.renderNormals);
  writeSchedule(out, s.schedule);
  for (const PairFriction& f : s.pairFriction) writePairFriction(out, f);
  out.value(static_cast<uint64_t>(s.cornerFriction.size()));
  for (const CornerFriction& c : s.cornerFriction) {
    out.value(c.rigid.index1);
    out.value(c.rigid.generation);
    out.value(c.corner);
    writePairFriction(out, c.state);
  }
  out.array(s.pendingImpulse);
}

void readDeformableState(StateReader& in, const DeformableBody& body, DeformableState* s) {
  const uint64_t nodes = static_cast<uint64_t>(body.nodeCount());
  readFiniteArray(in, &s->x, 3 * nodes, "deformable's node position count (3 per node)");
  readFiniteArray(in, &s->v, 3 * nodes, "deformable's node velocity count (3 per node)");
  readFiniteArray(in, &s->externalForce, 3 * nodes, "deformable's applied force count (3 per node)");
  readFiniteArray(in, &s->rotations, 4 * static_cast<uint64_t>(body.elementCount()),
                  "deformable's element rotation count (4 per element)");
  readFiniteArray(in, &s->lastNormalImpulse, nodes, "deformable's contact impulse count (1 per node)");
  in.array(&s->sliding, nodes, "deformable's sliding flag count (1 per node)");
  const uint64_t contacts = in.value<uint64_t>();
  if (in.ok() && contacts > nodes) in.outOfRange("a deformable's contact count");
  if (in.ok() && in.has(contacts, sizeof(int32_t) + 8 * sizeof(double) + 2 * sizeof(uint32_t))) {
    s->contacts.resize(static_cast<size_t>(contacts));
    for (NodeContact& c : s->contacts) {
      c.node = in.value<int32_t>();
      if (in.ok() && (c.node < 0 || static_cast<uint64_t>(c.node) >= nodes)) in.outOfRange("a contact's node");
      c.normal = readVec(in, "a contact's normal");
      c.colliderVelocity = readVec(in, "a contact's collider velocity");
      const double scalars[] = {in.value<double>(), in.value<double>()};
      in.requireFinite("a contact's speed or friction", scalars, 2);
      c.normalSpeed = scalars[0];
      c.friction = scalars[1];
      c.colliderIndex1 = in.value<uint32_t>();
      c.colliderGeneration = in.value<uint32_t>();
    }
  }
  const uint64_t render = body.renderPositions().size();
  readVecs(in, &s->renderPositions, render, "deformable's render vertex count");
  readVecs(in, &s->renderNormals, render, "deformable's render normal count");
  readSchedule(in, &s->schedule);
  // One friction state per node, as many as the body has (not counted in the buffer).
  if (in.ok() && in.has(nodes, kPairFrictionBytes)) {
    s->pairFriction.resize(static_cast<size_t>(nodes));
    for (PairFriction& f : s->pairFriction) readPairFriction(in, &f);
  }
  const uint64_t corners = in.value<uint64_t>();
  if (in.ok() && in.has(corners, 2 * sizeof(uint32_t) + sizeof(int32_t) + kPairFrictionBytes)) {
    s->cornerFriction.resize(static_cast<size_t>(corners));
    for (CornerFriction& c : s->cornerFriction) {
      c.rigid = PairBodyId{in.value<uint32_t>(), in.value<uint32_t>(), 1};
      c.corner = in.value<int32_t>();
      if (in.ok() && c.corner < 0) in.outOfRange("a rigid corner's index");
      readPairFriction(in, &c.state);
    }
  }
  readFiniteArray(in, &s->pendingImpulse, 3 * nodes, "deformable's pending impulse count (3 per node)");
}

void writeFluidState(StateWriter& out, const FluidState& s) {
  for (int a = 0; a < 3; ++a) {
    out.array(s.velocity[a]);
    out.array(s.open[a]);
    out.array(s.solidVelocity[a]);
    out.array(s.extrapolationMark[a]);
  }
  for (const Array<double>* a : {&s.smokeDensity, &s.temperature, &s.levelSet, &s.pressure, &s.cellWeights})
    out.array(*a);
  out.value(static_cast<uint64_t>(s.fractionColliders.size()));
  for (const FluidColliderPose& c : s.fractionColliders) {
    out.value(c.index1);
    out.value(c.generation);
    for (const Vec3* v : {&c.lo, &c.hi, &c.translation, &c.linearVelocity, &c.angularVelocity}) writeVec(out, *v);
    writeQuat(out, c.rotation);
  }
  out.value(static_cast<uint8_t>(s.fractionsValid));
  out.value(s.speedAtEnd);
  out.value(s.kineticAtEnd);
  out.value(s.targetVolume);
  out.value(static_cast<uint64_t>(s.loads.size()));
  for (const FluidColliderLoadState& l : s.loads) {
    out.value(l.index1);
    out.value(l.generation);
    writeVec(out, l.load.force);
    writeVec(out, l.load.torque);
    out.value(l.load.addedMass);
    writeVecs(out, l.vertexForces);
    writeVec(out, l.seen.linear);
    writeVec(out, l.seen.angular);
    writeVecs(out, l.drag.coefficient);
    writeVecs(out, l.drag.atRest);
    writeRigidDrag(out, l.rigidDrag);
  }
  out.value(static_cast<uint64_t>(s.solidMotions.size()));
  for (const SolidMotionHistory::Entry& e : s.solidMotions) {
    out.value(e.index1);
    out.value(e.generation);
    writeVec(out, e.motion.velocity);
    writeVec(out, e.motion.spin);
  }
  out.value(s.stepCount);
  out.value(s.lastStepSlices);
  out.array(s.slabs);
  out.array(s.sliceCostsMs);
  out.value(s.work);
  writeSchedule(out, s.schedule);
}

void readFluidState(StateReader& in, const FluidActor& fluid, FluidState* s) {
  const uint64_t cells = static_cast<uint64_t>(fluid.grid().cellCount());
  for (int a = 0; a < 3; ++a) {
    const uint64_t faces = fluid.grid().velocity[a].size();
    readFiniteArray(in, &s->velocity[a], faces, "fluid's face velocity count");
    readFiniteArray(in, &s->open[a], fluid.fractions().open[a].size(), "fluid's face fraction count");
    readFiniteArray(in, &s->solidVelocity[a], fluid.fractions().solidVelocity[a].size(),
                    "fluid's solid face velocity count");
    readEmptyOrFull(in, &s->extrapolationMark[a], faces, "fluid's extrapolation mark count");
  }
  readFiniteArray(in, &s->smokeDensity, fluid.smokeDensity().size(), "fluid's smoke density count");
  readFiniteArray(in, &s->temperature, fluid.temperature().size(), "fluid's temperature count");
  readFiniteArray(in, &s->levelSet, fluid.levelSet().size(), "fluid's level set count");
  readEmptyOrFull(in, &s->pressure, cells, "fluid's pressure count");
  readEmptyOrFull(in, &s->cellWeights, fluid.levelSet().empty() ? 0 : cells, "fluid's cell weight count");
  in.requireFinite("fluid's pressure", s->pressure.data(), s->pressure.size());
  in.requireFinite("fluid's cell weights", s->cellWeights.data(), s->cellWeights.size());
  // A fluid sees at most every collider of the world, whose ids are 32-bit.
  const uint64_t colliders = in.value<uint64_t>();
  constexpr size_t kPoseBytes = 2 * sizeof(uint32_t) + 19 * sizeof(double);
  if (in.ok() && in.has(colliders, kPoseBytes)) {
    s->fractionColliders.resize(static_cast<size_t>(colliders));
    for (FluidColliderPose& c : s->fractionColliders) {
      c.index1 = in.value<uint32_t>();
      c.generation = in.value<uint32_t>();
      for (Vec3* v : {&c.lo, &c.hi, &c.translation, &c.linearVelocity, &c.angularVelocity})
        *v = readVec(in, "a fluid's collider pose");
      c.rotation = readQuat(in, "a fluid's collider rotation");
    }
  }
  s->fractionsValid = in.value<uint8_t>() != 0;
  s->speedAtEnd = in.value<double>();
  s->kineticAtEnd = in.value<double>();
  s->targetVolume = in.value<double>();
  const double scalars[] = {s->speedAtEnd, s->kineticAtEnd, s->targetVolume};
  in.requireFinite("fluid's speed, energy or volume", scalars, 3);
  const uint64_t loads = in.value<uint64_t>();
  if (in.ok() && in.has(loads, 2 * sizeof(uint32_t) + 31 * sizeof(double) + 3 * sizeof(uint64_t))) {
    s->loads.resize(static_cast<size_t>(loads));
    for (FluidColliderLoadState& l : s->loads) {
      l.index1 = in.value<uint32_t>();
      l.generation = in.value<uint32_t>();
      l.load.force = readVec(in, "a fluid load");
      l.load.torque = readVec(in, "a fluid load");
      l.load.addedMass = in.value<double>();
      in.requireFinite("a fluid load", &l.load.addedMass, 1);
      // Checked against the deformable's surface when the world applies it.
      readVecsOfAnyCount(in, &l.vertexForces, "a fluid load's vertex forces");
      l.seen.linear = readVec(in, "a fluid load's solid acceleration");
      l.seen.angular = readVec(in, "a fluid load's solid acceleration");
      readVecDrag(in, l.vertexForces.size(), &l.drag);
      l.rigidDrag = readRigidDrag(in);
    }
  }
  const uint64_t motions = in.value<uint64_t>();
  if (in.ok() && in.has(motions, 2 * sizeof(uint32_t) + 6 * sizeof(double))) {
    s->solidMotions.resize(static_cast<size_t>(motions));
    for (SolidMotionHistory::Entry& e : s->solidMotions) {
      e.index1 = in.value<uint32_t>();
      e.generation = in.value<uint32_t>();
      e.motion.velocity = readVec(in, "a fluid's solid motion");
      e.motion.spin = readVec(in, "a fluid's solid motion");
    }
  }
  s->stepCount = in.value<uint64_t>();
  s->lastStepSlices = in.value<int32_t>();
  in.array(&s->slabs, static_cast<uint64_t>(FluidSlice::Count), "fluid's slice kind count");
  in.array(&s->sliceCostsMs, static_cast<uint64_t>(FluidSlice::Count), "fluid's slice cost count");
  in.requireFinite("fluid's slice costs", s->sliceCostsMs.data(), s->sliceCostsMs.size());
  s->work = in.value<WorkProgress>();
  if (in.ok() && (!s->work.valid() || s->lastStepSlices < 0))
    in.outOfRange("a fluid's step progress");
  readSchedule(in, &s->schedule);
}

}  // namespace vp

// What a saved world state holds of each actor: everything that evolves from step to step
// (vpWorldSaveState). What the host sets and the simulation never changes (shapes, meshes,
// materials, pins, attachments, filters, fluid controls, gravity, the budget) is not in it:
// a state is restored into the same world, or one built the same way, and the host's own
// settings stay as they are.
//
// Between two steps a fluid's working fields are the ones readers see (a step in progress is
// completed before its state is taken), so one copy of each field is enough.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/allocator.h"
#include "core/math_types.h"
#include "core/slice_sizer.h"
#include "core/work_progress.h"
#include "deform/deformable_contacts.h"
#include "deform/pair_contacts.h"
#include "fluid/solids/pressure_forces.h"
#include "fluid/solids/solid_motion_history.h"
#include "fluid/solids/surface_pressure_load.h"
#include "frame_plan.h"

namespace vp {

// A rigid body as Bullet integrates it (Bullet's scalars widened to double, which keeps
// them exactly), and the collider's own driving state around it. A transform is its basis
// row by row, then its origin.
struct RigidBodyState {
  double transform[12] = {}, interpolationTransform[12] = {}, motionStateTransform[12] = {};
  double linear[3] = {}, angular[3] = {}, interpolationLinear[3] = {}, interpolationAngular[3] = {};
  double totalForce[3] = {}, totalTorque[3] = {};
  int32_t activationState = 0;
  int32_t unused = 0;  // no padding: a state's bytes are all written
  double deactivationTime = 0.0, hitFraction = 1.0;
};

struct ColliderState {
  RigidBodyState body;
  Pose kinematicPose;
  Vec3 kinematicLinear = Vec3::Zero(), kinematicAngular = Vec3::Zero();
  std::optional<Pose> target;
  bool targetActive = false;
  Vec3 hostForce = Vec3::Zero(), hostTorque = Vec3::Zero();
  Vec3 contactLinear = Vec3::Zero(), contactMoment = Vec3::Zero();  // pending contact impulses
  Vec3 trackedVelocity = Vec3::Zero(), trackedSpin = Vec3::Zero();
  // The pose and velocity its exact geometry was last brought to (colliders with one).
  bool hasGeometry = false;
  Quat geometryRotation = Quat::Identity();
  Vec3 geometryTranslation = Vec3::Zero(), geometryLinear = Vec3::Zero(), geometryAngular = Vec3::Zero();
};

struct DeformableState {
  Array<double> x, v, externalForce, rotations, lastNormalImpulse;
  Array<uint8_t> sliding;
  Array<NodeContact> contacts;
  Array<Vec3> renderPositions, renderNormals;
  ActorSchedule schedule;
  // Contacts with deformables (deform/pair_contacts.h): per node, its friction state, those of
  // the rigid corners on its triangles, and the impulses the next step applies (3 per node).
  Array<PairFriction> pairFriction;
  Array<CornerFriction> cornerFriction;
  Array<double> pendingImpulse;
};

struct FluidColliderPose {
  uint32_t index1 = 0, generation = 0;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero(), linearVelocity = Vec3::Zero(), angularVelocity = Vec3::Zero();
};

struct FluidColliderLoadState {
  uint32_t index1 = 0, generation = 0;
  PressureLoad load;
  Array<Vec3> vertexForces;  // a deformable surface's
  SolidAcceleration seen;
  VertexDrag drag;      // a deformable surface's in a viscous fluid
  RigidDrag rigidDrag;  // a rigid body's in a viscous fluid
};

struct FluidState {
  Array<double> velocity[3];
  Array<double> smokeDensity, temperature, levelSet, pressure, cellWeights;
  Array<double> open[3], solidVelocity[3];  // the face fractions
  Array<uint8_t> extrapolationMark[3];
  std::vector<FluidColliderPose> fractionColliders;  // the colliders the fractions are of
  bool fractionsValid = false;
  double speedAtEnd = -1.0, kineticAtEnd = -1.0, targetVolume = 0.0;
  std::vector<FluidColliderLoadState> loads;
  std::vector<SolidMotionHistory::Entry> solidMotions;  // as the last step took them
  uint64_t stepCount = 0;
  int32_t lastStepSlices = 0;
  std::vector<SliceSizer::State> slabs;  // per FluidSlice kind
  std::vector<double> sliceCostsMs;       // per FluidSlice kind (core/sliced_job.h)
  WorkProgress work;
  ActorSchedule schedule;
};

}  // namespace vp

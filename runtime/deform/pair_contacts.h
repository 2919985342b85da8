// Contacts between deformables, and of a deformable with itself: a surface node of one body
// against a boundary triangle of another (or of its own, away from the node's neighbourhood).
// A node's contact with a dynamic rigid body is the same spring with a point of the rigid body
// on its other side (PairContact::rigidSide), whose six velocities join the solve; so is a
// rigid body's corner against a deformable's triangle (PairContact::rigidNode), without which a
// box smaller than the deformable's elements falls between its nodes. A round body (sphere,
// capsule, cylinder) has no corners: each triangle near it is touched by the body's point
// deepest under the triangle's plane, its friction state keyed by the triangle.
//
// Bodies that step together solve one system (contact_group_solve.h) and the contact couples
// their new velocities (PairContact::coupled). Otherwise each steps from the state the other
// had when the frame began, so neither step sees the other body's new velocities. A hard
// constraint to the other body's old velocity, with its reaction sent one step late, is a
// delayed feedback loop: a stack of two jellies chattered. Each contact is instead a stiff
// spring along the triangle's normal, with
// a tangential spring that sticks (its anchor carried from step to step)
// until its force leaves Coulomb's cone, then slides with kinetic friction mu times its last
// normal impulse, as collider contacts do. Each body treats its own side of the spring
// implicitly (the spring's stiffness on its diagonal) and the other side at the state of the
// frame's start (docs/choices.md: why the loop's gain stays below one).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/collision_filter.h"
#include "core/math_types.h"
#include "core/task_system.h"
#include "collide/face_coverage.h"
#include "deform/contact_surface.h"

namespace vp {

// The spring's stiffness over h² as a multiple of the pair's reduced mass: the loop gain of
// one side is k h² / (m + k h²), so the two-body loop's gain is below (kStiffness / (1 +
// kStiffness))² and the penetration at rest is g h² / kStiffness over the share of the
// body's weight the contact nodes carry.
constexpr double kPairContactStiffness = 8.0;
// The same for a contact whose two sides are solved in one system (PairContact::coupled): no
// loop gain bounds it there, only the solve's conditioning, and the penetration at rest shrinks
// with it.
constexpr double kCoupledPairContactStiffness = 64.0;
// How deep below a triangle a node still counts as touching it, in mean element edges: deeper
// points are on another part of the surface (a convex edge's other face).
constexpr double kPairContactDepthEdges = 0.5;

// A contact whose node pushed in its last step holds until the predicted gap reaches this
// many rest gaps (a fresh one begins below one). The spring acts both ways, so a node
// separating slower than about a rest gap per step is pulled back for that one step; its
// normal impulse then pulls, its state starts afresh and the next step lets it go.
constexpr double kPairContactKeep = 2.0;

// Below this slip speed (m/s) a sliding contact sticks again (ContactActiveSet::kSlipSpeed's rule).
constexpr double kPairSlipSpeed = 1e-4;
// A contact that begins with its node slipping at least this fast (m/s) begins sliding: a
// fresh stick spring would stop the slip within the step, beyond Coulomb's cone. Slower
// arrivals stick, as a resting stack's contacts that come and go at its rim must.
constexpr double kPairArrivingSlipSpeed = 1e-2;

// Which deformable a contact touched, by its handle: list positions shift when a deformable
// before it is destroyed, and a friction state carried by position would be taken up by
// another pair.
struct PairBodyId {
  uint32_t index1 = 0, generation = 0;  // index1 0: none
  uint8_t rigid = 0;                    // 1: a collider's handle, else a deformable's
  bool operator==(const PairBodyId& o) const {
    return index1 == o.index1 && generation == o.generation && rigid == o.rigid;
  }
};

// A node's tangential spring, carried from its last step (kept by the node's body).
struct PairFriction {
  // The stick spring's force (N), in the last contact's tangent plane: a force, not a stretch,
  // so that it carries over when the spring's stiffness changes (coupled or not, another dt).
  Vec3 stick = Vec3::Zero();
  double lastNormalImpulse = 0.0;  // N s
  PairBodyId other;                // the body whose triangle it touched
  uint8_t sliding = 0;
};

// A rigid body's corner's tangential spring on a deformable, carried from its last step (kept by
// the deformable, since the world keeps no state of its own for a rigid body).
struct CornerFriction {
  PairBodyId rigid;     // the corner's body
  int32_t corner = -1;  // rigidVertices' numbering
  PairFriction state;   // state.other: the deformable
};

struct PairContact {
  // The node side (rigidNode: a rigid pair body and its corner, or for a round body the
  // triangle whose plane its point is deepest under).
  int32_t nodeBody = -1, node = -1;
  // The other side: a triangle (the node's own body: self contact) or, with rigidSide, a rigid
  // body, whose pair body index follows the deformables' (findPairContacts).
  int32_t triangleBody = -1;
  PairBodyId triangleBodyId;         // its handle
  std::array<int32_t, 3> triangleNodes{{-1, -1, -1}};
  Vec3 weights = Vec3::Zero();       // the contact point's barycentric weights (rigid: 1, 0, 0)
  bool rigidSide = false;
  // The node side is a corner of a dynamic rigid body (rigidVertices' numbering), whose pair body
  // index follows the deformables'; its friction state is kept by the triangle's body.
  bool rigidNode = false;
  PairBodyId nodeBodyId;             // rigidNode: the rigid body's handle
  Vec3 arm = Vec3::Zero();           // rigid (either side): the contact point less the body's centre of mass
  // An attachment of the node to the rigid body (DeformableBody::attachmentSprings), not a
  // contact: a spring with no rest length that never slides, keeps no friction state and
  // makes no contact events.
  bool attachment = false;
  Vec3 normal = Vec3::UnitY();       // out of the triangle (the rigid body)
  double gap = 0.0;                  // (node − contact point)·normal at the frame's start
  double rest = 0.0;                 // the spring's rest gap
  double reducedMass = 0.0;          // of the node and the triangle's point
  double friction = 0.0;             // combined coefficient (product of the bodies')
  Vec3 nodeVelocity = Vec3::Zero();
  std::array<Vec3, 3> triangleVelocities{};  // rigid: the point's velocity first
  PairFriction state;                // the node's friction state, stick projected on the tangent plane
  // Both sides solved in one system this step (deform/contact_group_solve.h): each side sees
  // the other's new velocities instead of those at the frame's start.
  bool coupled = false;

  // h² k, the spring's stiffness times the step squared.
  double springH2k() const {
    return (coupled ? kCoupledPairContactStiffness : kPairContactStiffness) * reducedMass;
  }

  // The contact point's velocity at the frame's start.
  Vec3 triangleVelocity() const {
    return weights[0] * triangleVelocities[0] + weights[1] * triangleVelocities[1] + weights[2] * triangleVelocities[2];
  }
  // The node's slip over the triangle at the frame's start: its tangential relative velocity.
  Vec3 startSlip() const {
    const Vec3 u = nodeVelocity - triangleVelocity();
    return u - u.dot(normal) * normal;
  }
  // The gap at the end of a step of h at the frame's start velocities.
  double predictedGap(double h) const { return gap + h * (nodeVelocity - triangleVelocity()).dot(normal); }
};

// What detection reads of one body, at the frame's start.
struct PairContactBody {
  PairBodyId id;                         // the body's handle
  const Array<double>* x = nullptr;      // 3 per node
  const Array<double>* v = nullptr;
  const Array<double>* mass = nullptr;   // per node
  const Array<int32_t>* surfaceNodes = nullptr;
  const ContactSurface* surface = nullptr;  // refit to x and the step's motion (ContactSurface::refit)
  const Array<PairFriction>* friction = nullptr;  // per node
  const Array<CornerFriction>* cornerFriction = nullptr;  // of the rigid corners on its triangles
  CollisionFilter filter;
  double frictionCoefficient = 0.5;  // the body's Coulomb coefficient
  double rest = 0.0;       // its contact margin: the spring's rest gap for its nodes
  double depth = 0.0;      // kPairContactDepthEdges mean edges
  bool selfCollision = false;
  bool touchesRigid = false;  // its contacts with dynamic rigid bodies are pair contacts this step
};

// What detection and the solve read of a dynamic rigid body, after the frame's rigid step.
struct RigidContactBody {
  PairBodyId id;                              // the collider's handle (rigid = 1)
  const PreparedCollider* geometry = nullptr;  // at its current pose
  Vec3 centre = Vec3::Zero();                 // of mass: its origin
  Mat3 rotation = Mat3::Identity();           // its pose's: world = rotation * local + centre
  Vec3 linearVelocity = Vec3::Zero(), angularVelocity = Vec3::Zero();
  // What its next rigid step is expected to add to them besides the deformables' contacts: what
  // its last one did (gravity, its contacts in Bullet, loads).
  Vec3 velocityChange = Vec3::Zero(), spinChange = Vec3::Zero();
  double mass = 0.0;
  Mat3 inertia = Mat3::Identity();            // about the centre, in the world frame
  CollisionFilter filter;
  double frictionCoefficient = 0.5;
  Vec3 pointVelocity(const Vec3& arm) const { return linearVelocity + angularVelocity.cross(arm); }
  // How far any of its points can move over a step of h.
  // How far its points move in a step of h, seen from a frame moving at `frame` (a deformable
  // surface's boxes' frame, ContactSurface::frameVelocity).
  double sweep(double h, const Vec3& frame) const {
    return h * ((linearVelocity - frame).norm() + angularVelocity.norm() * geometry->boundRadius);
  }
};

// The corners a rigid body's shape pokes into a deformable with (world frame, at its pose): a
// box's eight, a hull's points, a mesh's vertices; none for round shapes (their points come
// from the triangles they touch) and planes.
void rigidVertices(const PreparedCollider& shape, Array<Vec3>* out);

// The rigid body of `rigids` with the collider handle (index1, generation), or null.
const RigidContactBody* findRigidBody(const std::vector<RigidContactBody>& rigids, uint32_t index1,
                                      uint32_t generation);

// Every surface node's nearest touching triangle (the lowest predicted gap over the step h)
// among the bodies its filter meets and, with selfCollision, its own, or, for a body whose
// touchesRigid is set, the nearest rigid body's surface if that is nearer; then every rigid
// body's corners' nearest touching triangles among the bodies whose touchesRigid is set and
// whose filter meets its; in body, node order, then rigid body, corner order (the same for any
// worker count). Rigid body r is pair body bodies.size() + r.
void findPairContacts(const std::vector<PairContactBody>& bodies, const std::vector<RigidContactBody>& rigids,
                      double h, TaskSystem& tasks, std::vector<PairContact>* out);

}  // namespace vp

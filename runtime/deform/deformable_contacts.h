// Contacts between a deformable's surface nodes and the rigid colliders, as velocity
// constraints of the implicit solve (no penalty springs, so no tiny time steps):
//
// 1. Detection: a surface node is in contact with a collider when, moving with its current
//    velocity relative to the collider, it would end the step inside it or within `margin`
//    of it (signed distance of the collider's exact geometry, normal from the distance
//    gradient). The deepest such collider wins.
// 2. In the solve a contact first sticks: its velocity is prescribed as the collider's, with
//    the normal part v·n = v_c·n − φ/h (it lands on the surface, or leaves it by the
//    penetration depth when it starts inside); CG filters constrained directions (Baraff &
//    Witkin 1998), so this is exact, not a penalty.
// 3. The constraint impulses J = A v' − b then decide, by Coulomb's law, one active-set pass:
//    J·n < 0 (pulling in) releases the contact; a tangential impulse outside the friction
//    cone turns it into a sliding contact (normal velocity prescribed, kinetic friction
//    impulse μ J·n against the slip on the right-hand side); then the system is re-solved.
//    Static friction is therefore implicit: a cube on an incline below the friction angle
//    does not creep.
// The combined friction coefficient is the product of the deformable's and the collider's
// (Bullet's rule, so mixed scenes behave alike).
#pragma once

#include <cstdint>
#include <vector>

#include "collide/face_coverage.h"
#include "core/allocator.h"
#include "core/math_types.h"

namespace vp {

struct ContactCollider {
  const PreparedCollider* geometry = nullptr;
  double friction = 0.5;
  uint32_t index1 = 0, generation = 0;  // the collider's handle, carried into its contacts
  bool dynamic = false;                 // pushed back: the step reports its contact reactions
};

// What one contact of a deformable's step did to a dynamic collider: the impulse (N s) equal
// and opposite to the constraint impulse on the node, at the node's position.
struct ContactReaction {
  uint32_t colliderIndex1 = 0, colliderGeneration = 0;
  Vec3 point = Vec3::Zero();
  Vec3 impulse = Vec3::Zero();
};

struct NodeContact {
  int32_t node = -1;
  Vec3 normal = Vec3::UnitY();          // out of the collider
  Vec3 colliderVelocity = Vec3::Zero();  // of the collider's material point at the node
  double normalSpeed = 0.0;              // prescribed v·n
  double friction = 0.0;                 // combined coefficient
  uint32_t colliderIndex1 = 0, colliderGeneration = 0;  // which collider (ContactCollider's handle)
};

// Push-out speed cap for nodes that start inside a collider: resolves deep penetrations
// over several steps instead of launching the body.
constexpr double kMaxPushOutSpeed = 2.0;

// The unit gradient of the collider's signed distance at x: its outward normal there.
Vec3 colliderNormal(const PreparedCollider& c, const Vec3& x);

void findNodeContacts(const Array<double>& x, const Array<double>& v, const Array<int32_t>& surfaceNodes,
                      const std::vector<ContactCollider>& colliders, double h, double bodyFriction, double margin,
                      Array<NodeContact>* out);

}  // namespace vp

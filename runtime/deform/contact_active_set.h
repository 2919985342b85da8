// The contact constraints of a deformable's implicit step and Coulomb's law on them. Each step
// finds the surface nodes about to touch a collider; a contact sticks (its whole velocity
// prescribed: the collider's tangential velocity and the landing normal speed) unless it slid
// last step, when only its normal velocity is prescribed and kinetic friction from its last
// normal impulse opposes its slip. After a solve, the impulses the constraints applied
// (J = A v' − b at their nodes) drive the active-set passes:
// - a contact whose normal impulse pulls the node in is released (lift-off);
// - a sticking contact whose tangential impulse leaves the cone |J_t| <= μ J_n slides, with
//   the kinetic friction impulse μ J_n (along the impulse it needed) on the right-hand side;
// - a sliding contact whose slip the friction reversed sticks again (the friction impulse
//   would have been more than static friction needed).
// Which contacts slide, and their last normal impulses, carry into the next step.
#pragma once

#include "core/allocator.h"
#include "core/math_types.h"
#include "deform/deformable_contacts.h"
#include "deform/node_constraints.h"
#include "snapshot/actor_states.h"

#include <vector>

namespace vp {

// A node's velocity relative to the collider, in the contact's tangent plane.
Vec3 tangentialSlip(const Vec3& velocity, const NodeContact& contact);

class ContactActiveSet {
 public:
  // Below this tangential speed (m/s) a contact counts as not slipping and sticks next step.
  static constexpr double kSlipSpeed = 1e-4;

  void resize(int32_t nodeCount);
  // The step's contacts of the surface nodes at x moving along `motion` (3 per node) against
  // `colliders` over h; nodes already held (kFixed) ignore them. Marks each contact's node
  // stuck or sliding in `held` and writes its prescribed velocity into vNext.
  void begin(const Array<double>& x, const Array<double>& v, const Array<double>& motion,
             const Array<int32_t>& surfaceNodes, const std::vector<ContactCollider>& colliders, double h,
             double friction, double margin, NodeConstraints* held, Array<double>* vNext);
  // Adds the sliding contacts' kinetic friction impulses to the right-hand side.
  void addFriction(Array<double>* rhs) const;
  // One pass of Coulomb's law on the contacts' impulses (one per contact, in order): releases,
  // slides and re-sticks as the header says, keeping rhs and vNext in step. Returns whether
  // any contact changed.
  bool applyCoulomb(const Array<Vec3>& impulses, NodeConstraints* held, Array<double>* vNext, Array<double>* rhs);
  // After the last pass: which contacts slide into the next step.
  void rememberSliding(const Array<double>& vNext, const NodeConstraints& held);

  const Array<NodeContact>& contacts() const { return contacts_; }
  const Array<Vec3>& frictionImpulses() const { return friction_; }  // one per contact

  void saveTo(DeformableState* state) const;
  void restoreFrom(DeformableState* state);  // moves the contact arrays out of it

 private:
  Array<NodeContact> contacts_;
  Array<Vec3> friction_;         // kinetic friction impulse of each contact this step
  Array<uint8_t> sliding_;       // per node: slid last step
  Array<double> lastNormalImpulse_;  // per node
};

}  // namespace vp

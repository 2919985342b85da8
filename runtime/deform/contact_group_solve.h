// One implicit solve for deformables that touch each other.
//
// A pair contact couples the velocities of the node's body and the triangle's. Solving each
// body on its own, with the other side at its frame-start velocity, is one Jacobi sweep over
// the bodies: the contact must be soft for that loop to settle (pair_contacts.h), a stack sinks
// into its springs and a stick spring on a slope creeps. Here the bodies a frame's coupled
// contacts join (PairContact::coupled) solve one system,
//
//   [ A_1 + D_1     C_12   … ] [ v'_1 ]   [ b_1 ]
//   [   C_21     A_2 + D_2 … ] [ v'_2 ] = [ b_2 ],
//
// each A_b its step matrix, D_b the contacts' diagonal blocks and C the springs' blocks
// between different nodes (addPairCouplingProduct), applied without storing them. The springs'
// Hessians are positive semi-definite, so the system is SPD and one CG solves it, each body's
// block preconditioned by its own preconditioner and filtered by its own constraints. The
// collider contacts' Coulomb passes run as in a lone step, each pass re-solving the whole group.
// A lone body is a group of one (its solve may run on the device; a group's runs on the CPU).
//
// A dynamic rigid body that the members' contacts touch (PairContact::rigidSide, rigidNode) joins with
// its six velocities u = (V, Ω): its rows are M u' + Σ J^T D (v' + J u') = M (u + h g) + Σ J^T c,
// M its mass and world inertia, J = [−I, [arm]×] each contact's, so that the contacts'
// impulses are those of the rigid body's new velocity, not of its old one. Its block is 6×6,
// preconditioned by its inverse. The rigid body's step itself is Bullet's, in the next frame:
// the world hands it the contacts' impulses (DeformableBody::contactReactions), and a body
// that touches nothing else moves as solved here. What else acts on it (its contacts in
// Bullet, damping, fluid and host loads) the solve does not see.
#pragma once

#include <vector>

#include "deform/deformable_body.h"
#include "deform/pair_contact_terms.h"

namespace vp {

struct ContactGroupMember {
  DeformableBody* body = nullptr;
  const DeformableStepInput* input = nullptr;  // dt, deadlines, pair contacts: the first member's hold for all
  PhaseTimer* timer = nullptr;
  ActorStats* stats = nullptr;
};

// One step of every member: each begins (DeformableBody::beginStep), one solve, each finishes.
// The members share dt and the pair contacts; the first member's deadlines bound the solve.
// Every member's stats report the group's iterations and residual; the solve's time is in the
// first member's phases, each member's own stages in its own. When one member's step blows up,
// every member's is discarded.
void stepContactGroup(const std::vector<ContactGroupMember>& members);

class ContactGroupSolve {
 public:
  explicit ContactGroupSolve(const std::vector<ContactGroupMember>& members);
  // CG and the collider contacts' passes; returns whether the solve reached the accuracy floor.
  bool solve();
  // The members' solved velocities by pair body (DeformableBody::finishStep's `solved`).
  PairVelocities solvedVelocities() const;

 private:
  CgResult solveOnce(const CgSettings& settings);
  void refreshPreconditioners();
  // Whether a Coulomb pass changed any member's contacts.
  bool coulombPass();
  void lap(Phase phase);
  // x_ = every member's current solved velocities (the rigid members' too).
  void gatherVelocities();
  // Each member's pair_.coupling at the members' current solved velocities.
  void storeCouplingProduct();

  // A dynamic rigid body in the solve (see above): pair body pairBody, at offset in the vectors.
  struct RigidMember {
    int32_t pairBody = -1;
    const RigidContactBody* body = nullptr;
    int64_t offset = 0;
    Mat6 block = Mat6::Zero(), inverse = Mat6::Zero();
    Vec6 rhs = Vec6::Zero();
    Array<double> velocity;  // 6: the solved u'
  };
  void addRigidMembers();

  const std::vector<ContactGroupMember>& members_;
  std::vector<RigidMember> rigids_;
  const DeformableStepInput& in_;  // the first member's
  std::vector<int64_t> memberOffset_;  // scalars before member m in the group's vectors
  std::vector<int64_t> pairOffset_;    // the same by pair body (−1: not a member)
  int64_t size_ = 0;
  std::vector<PairContact> coupledPairs_;  // the coupled contacts among the members
  bool coupled_ = false;                   // coupledPairs_ is not empty
  double floor_ = 0.0;    // the strictest member's accuracy floor
  Array<double> b_, x_, product_;
  CgWorkspace work_;
};

}  // namespace vp

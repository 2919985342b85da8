#include "deform/contact_group_solve.h"

#include <algorithm>

#include "deform/pair_contact_terms.h"

namespace vp {
namespace {

// Contact active-set passes per step: each may re-solve once. Four settle stick/slide/
// release decisions in practice; a budget-cut step simply stops earlier.
constexpr int kContactPasses = 4;

}  // namespace

void stepContactGroup(const std::vector<ContactGroupMember>& members) {
  // In a group each member's timer holds its own stages; the shared solve is the first's.
  const bool group = members.size() > 1;
  for (const ContactGroupMember& m : members) {
    if (group) m.timer->restart();
    m.body->beginStep(*m.input, *m.timer);
  }
  if (group) members.front().timer->restart();
  ContactGroupSolve solve(members);
  const bool reachedFloor = solve.solve();
  const PairVelocities solved = solve.solvedVelocities();
  bool diverged = false;
  for (const ContactGroupMember& m : members) {
    if (group) m.timer->restart();
    m.body->finishStep(*m.input, reachedFloor, solved, *m.timer, m.stats);
    diverged = diverged || m.stats->diverged;
  }
  // The members' steps share their contacts' impulses: one that blew up takes the others back too.
  if (!diverged) return;
  for (const ContactGroupMember& m : members)
    if (!m.stats->diverged) {
      m.body->discardStep(*m.input->tasks);
      m.stats->diverged = true;
    }
}

ContactGroupSolve::ContactGroupSolve(const std::vector<ContactGroupMember>& members)
    : members_(members), in_(*members.front().input) {
  int32_t pairBodies = 0;
  for (const ContactGroupMember& m : members_) pairBodies = std::max(pairBodies, m.input->pairBody + 1);
  pairOffset_.assign(static_cast<size_t>(pairBodies), -1);
  floor_ = members_.front().body->desc_.solver.targetResidual;
  for (const ContactGroupMember& m : members_) {
    memberOffset_.push_back(size_);
    if (m.input->pairBody >= 0) pairOffset_[static_cast<size_t>(m.input->pairBody)] = size_;
    size_ += 3 * static_cast<int64_t>(m.body->nodeCount_);
    floor_ = std::min(floor_, m.body->desc_.solver.targetResidual);
  }
  auto member = [&](int32_t body) { return body < pairBodies && pairOffset_[static_cast<size_t>(body)] >= 0; };
  // The group's coupled contacts, so that each CG iteration visits only them.
  if (in_.pairContacts)
    for (const PairContact& p : *in_.pairContacts)
      if (p.coupled && (member(p.nodeBody) || member(p.triangleBody))) coupledPairs_.push_back(p);
  coupled_ = !coupledPairs_.empty();
  addRigidMembers();
}

void ContactGroupSolve::addRigidMembers() {
  for (const PairContact& p : coupledPairs_) {
    if (!p.rigidSide && !p.rigidNode) continue;
    const int32_t pairBody = p.rigidSide ? p.triangleBody : p.nodeBody;
    const size_t b = static_cast<size_t>(pairBody);
    if (b >= pairOffset_.size()) pairOffset_.resize(b + 1, -1);
    if (pairOffset_[b] >= 0) continue;
    RigidMember r;
    r.pairBody = pairBody;
    r.body = &in_.rigidBody(pairBody);
    r.offset = pairOffset_[b] = size_;
    size_ += 6;
    const RigidContactBody& R = *r.body;
    r.block.topLeftCorner<3, 3>() = R.mass * Mat3::Identity();
    r.block.bottomRightCorner<3, 3>() = R.inertia;
    Vec6 u, expected;
    u << R.linearVelocity, R.angularVelocity;
    expected << R.linearVelocity + R.velocityChange, R.angularVelocity + R.spinChange;
    r.rhs = r.block * expected;
    addRigidContactTerms(coupledPairs_, r.pairBody, in_.dt, &r.block, &r.rhs);
    r.inverse = r.block.inverse();
    r.velocity.resize(6);
    Eigen::Map<Vec6>(r.velocity.data()) = u;
    rigids_.push_back(std::move(r));
  }
}

PairVelocities ContactGroupSolve::solvedVelocities() const {
  PairVelocities solved(pairOffset_.size(), nullptr);
  for (const ContactGroupMember& m : members_)
    if (m.input->pairBody >= 0) solved[static_cast<size_t>(m.input->pairBody)] = &m.body->vNext_;
  for (const RigidMember& r : rigids_) solved[static_cast<size_t>(r.pairBody)] = &r.velocity;
  return solved;
}

void ContactGroupSolve::lap(Phase phase) { members_.front().timer->lap(phase); }

void ContactGroupSolve::refreshPreconditioners() {
  bool refreshed = false;
  for (const ContactGroupMember& m : members_) {
    DeformableBody& body = *m.body;
    if (!body.preconditioner_.needsRefresh() || body.deviceSolve_) continue;
    body.refreshPreconditioner(*in_.tasks, body.massScale(in_.dt));
    refreshed = true;
  }
  if (refreshed) lap(Phase::Assemble);  // the preconditioner's setup is part of building the system
}

bool ContactGroupSolve::coulombPass() {
  bool touched = false, changed = false;
  for (const ContactGroupMember& m : members_) {
    DeformableBody& body = *m.body;
    if (body.contacts_.contacts().empty()) continue;
    Array<Vec3> impulses;
    body.contactImpulses(*in_.tasks, &impulses);
    changed = body.contacts_.applyCoulomb(impulses, &body.held_, &body.vNext_, &body.rhs_) || changed;
    touched = true;
  }
  if (touched) lap(Phase::Contacts);
  return changed;
}

bool ContactGroupSolve::solve() {
  TaskSystem& tasks = *in_.tasks;
  CgSettings settings{members_.front().body->desc_.solver.tolerance, 0};
  for (const ContactGroupMember& m : members_) {
    settings.relativeTolerance = std::min(settings.relativeTolerance, m.body->desc_.solver.tolerance);
    settings.maxIterations = std::max(settings.maxIterations, m.body->desc_.solver.maxIterations);
  }
  if (in_.solverMaxIterations > 0) settings.maxIterations = in_.solverMaxIterations;
  for (const ContactGroupMember& m : members_) m.body->choosePreconditioner(in_.dt);
  refreshPreconditioners();
  CgResult cg = solveOnce(settings);
  int iterations = cg.iterations;
  lap(Phase::Solve);

  // Coulomb's law on the constraint impulses (deform/contact_active_set.h): a few passes,
  // each re-solve starting from the last iterate, so it is cheap.
  for (int pass = 0; pass < kContactPasses && coulombPass(); ++pass) {
    // Past the accuracy floor's deadline a re-solve would run no iteration, and the multigrid
    // refresh before it is the costliest part of a pass: the last solve's velocities stand.
    // Only that deadline skips it: a released node kept at its collider's velocity glues the
    // body to a moving collider frame after frame.
    if (in_.floorDeadline.expired()) {
      cg.budgetCut = true;
      storeCouplingProduct();  // the pass moved vNext_ after the last solve
      break;
    }
    // With the filters of the pass before, a released node or a newly sliding contact's
    // tangent lies in a multigrid's null space, CG cannot reduce the residual there and the
    // solve stalls (relative residual ~1 after hundreds of iterations).
    refreshPreconditioners();
    cg = solveOnce(settings);
    iterations += cg.iterations;
    lap(Phase::Solve);
  }
  for (const ContactGroupMember& m : members_) {
    DeformableBody& body = *m.body;
    body.contacts_.rememberSliding(body.vNext_, body.held_);
    body.recordReactions(tasks, *m.input, solvedVelocities());
    PhaseStats& solve = m.stats->phase(Phase::Solve);
    solve.iterations = iterations;
    solve.residual = cg.relativeResidual;
    solve.budgetCut = cg.budgetCut;
    m.stats->onDevice = body.deviceSolve_ != nullptr;
    m.stats->residual = cg.relativeResidual;
    // Missed only when time ran out: a solve that stopped at maxIterations above the floor
    // is a matter of the solver settings, which a lower rate would not change.
    m.stats->floorMissed = cg.budgetCut && cg.relativeResidual > floor_;
  }
  return !cg.budgetCut || cg.relativeResidual <= floor_;
}

CgResult ContactGroupSolve::solveOnce(const CgSettings& settings) {
  TaskSystem& tasks = *in_.tasks;
  LinearSystem system;
  system.size = size_;
  system.apply = [&](const double* x, double* y) {
    for (size_t m = 0; m < members_.size(); ++m)
      members_[m].body->matrix_.multiply(tasks, x + memberOffset_[m], y + memberOffset_[m]);
    for (const RigidMember& r : rigids_) Eigen::Map<Vec6>(y + r.offset) = r.block * Eigen::Map<const Vec6>(x + r.offset);
    if (coupled_) addPairCouplingProduct(coupledPairs_, pairOffset_, x, y);
  };
  system.precondition = [&](const double* r, double* z) {
    for (size_t m = 0; m < members_.size(); ++m)
      members_[m].body->preconditioner_.apply(tasks, r + memberOffset_[m], z + memberOffset_[m]);
    for (const RigidMember& rigid : rigids_)
      Eigen::Map<Vec6>(z + rigid.offset) = rigid.inverse * Eigen::Map<const Vec6>(r + rigid.offset);
  };
  system.filter = [&](double* v) {
    for (size_t m = 0; m < members_.size(); ++m) members_[m].body->held_.filter(tasks, v + memberOffset_[m]);
  };
  DeformableBody& first = *members_.front().body;
  if (members_.size() == 1 && !coupled_) return first.solveLinearSystem(in_, system, settings, first.massScale(in_.dt));

  // The members' right-hand sides and warm starts in one vector each.
  const bool alone = members_.size() == 1 && rigids_.empty();
  if (!alone) {
    b_.resize(static_cast<size_t>(size_));
    gatherVelocities();
    for (size_t m = 0; m < members_.size(); ++m) {
      const DeformableBody& body = *members_[m].body;
      std::copy(body.rhs_.begin(), body.rhs_.end(), b_.begin() + memberOffset_[m]);
    }
    for (const RigidMember& r : rigids_) Eigen::Map<Vec6>(b_.data() + r.offset) = r.rhs;
  }
  double* x = alone ? first.vNext_.data() : x_.data();
  const CgResult cg = solveConjugateGradient(tasks, system, alone ? first.rhs_.data() : b_.data(), x, settings,
                                             in_.deadline, alone ? first.cg_ : work_, floor_, in_.floorDeadline);
  if (!alone) {
    for (size_t m = 0; m < members_.size(); ++m) {
      DeformableBody& body = *members_[m].body;
      std::copy(x + memberOffset_[m], x + memberOffset_[m] + static_cast<int64_t>(body.vNext_.size()),
                body.vNext_.begin());
    }
    for (RigidMember& r : rigids_) std::copy(x + r.offset, x + r.offset + 6, r.velocity.begin());
  }
  storeCouplingProduct();
  return cg;
}

void ContactGroupSolve::gatherVelocities() {
  x_.resize(static_cast<size_t>(size_));
  for (size_t m = 0; m < members_.size(); ++m) {
    const DeformableBody& body = *members_[m].body;
    std::copy(body.vNext_.begin(), body.vNext_.end(), x_.begin() + memberOffset_[m]);
  }
  for (const RigidMember& r : rigids_) std::copy(r.velocity.begin(), r.velocity.end(), x_.begin() + r.offset);
}

void ContactGroupSolve::storeCouplingProduct() {
  if (!coupled_) return;
  // What the coupling adds to A v' at each node, at the members' current v': the contacts'
  // impulses read it.
  gatherVelocities();
  product_.assign(static_cast<size_t>(size_), 0.0);
  addPairCouplingProduct(coupledPairs_, pairOffset_, x_.data(), product_.data());
  for (size_t m = 0; m < members_.size(); ++m) {
    DeformableBody& body = *members_[m].body;
    const auto first = product_.begin() + memberOffset_[m];
    body.pair_.coupling.assign(first, first + static_cast<int64_t>(body.vNext_.size()));
  }
}

}  // namespace vp

// The deformables' stage of a world step (frame_plan.h has the policy): the frame's plan for
// them, their contacts found once, the contact groups stepped within their deadlines, then the
// plan's bookkeeping.
#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

#include "core/log.h"
#include "deform/contact_group_solve.h"
#include "deform/contact_groups.h"
#include "deform/pair_contact_settlement.h"
#include "world.h"
#include "world_stages.h"

namespace vp {

// The deformables of one frame, by handle order.
struct World::DeformableFrame {
  std::vector<DeformableHandle> handles;
  std::vector<DeformableBody*> bodies;
  std::vector<FramePlan::Deformable> planned;  // each body's priority and schedule
  std::vector<bool> due;    // it steps this frame
  std::vector<int> served;  // the due ones, by priority
  std::vector<ActorStats> actors;
  std::vector<FramePlan::DeformableDeadlines> deadlines;  // of the due ones
};

namespace {

// Whether a deformable can meet one of the boxes `reach` within `lookahead` seconds at its
// fastest node's speed.
bool withinReach(const DeformableBody& body, const std::vector<Filtered<Aabb>>& reach, double lookahead) {
  double fastest = 0.0;
  const Array<double>& v = body.velocities();
  for (size_t i = 0; i + 2 < v.size(); i += 3)
    fastest = std::max(fastest, v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2]);
  const Aabb bounds = body.bounds();
  const Vec3 travel = Vec3::Constant(lookahead * std::sqrt(fastest));
  const Aabb box{bounds.lo - travel, bounds.hi + travel};
  return std::any_of(reach.begin(), reach.end(), [&](const Filtered<Aabb>& r) {
    return r.filter.meets(body.desc().filter) && r.entry.overlaps(box);
  });
}

// A deformable step's slices are its non-iterative phases and its solver's iterations.
double longestDeformableSliceMs(const ActorStats& a) {
  double longest = 0.0;
  for (int p = 0; p < kPhaseCount; ++p) {
    const PhaseStats& phase = a.phases[p];
    const bool iterative = static_cast<Phase>(p) == Phase::Solve;
    longest = std::max(longest, iterative && phase.iterations > 0 ? phase.ms / phase.iterations : phase.ms);
  }
  return longest;
}

// What deformables may touch: every collider with exact geometry, with its filter.
std::vector<Filtered<ContactCollider>> deformableContactColliders(const SlotMap<Collider>& colliders) {
  std::vector<Filtered<ContactCollider>> out;
  colliders.forEach([&](ColliderHandle h, const Collider& c) {
    if (c.geometry())
      out.push_back({c.filter(), ContactCollider{c.geometry(), c.desc().friction, h.index1, h.generation,
                                                 c.bodyType() == BodyType::Dynamic}});
  });
  return out;
}

// A contact group is planned as one actor: its first member's schedule at the members' highest
// interval, with every member's tail; paced as its most constrained member (Pacing's order).
FramePlan::Deformable groupAsOne(const std::vector<FramePlan::Deformable>& planned, const std::vector<int>& members,
                                 ActorSchedule* schedule) {
  const FramePlan::Deformable& first = planned[members.front()];
  *schedule = *first.schedule;
  double tailsMs = 0.0;
  FramePlan::Pacing pacing = FramePlan::Pacing::Own;
  for (int i : members) {
    const ActorSchedule& s = *planned[i].schedule;
    tailsMs += std::max(s.tailMs, 0.0);
    schedule->interval = std::max(schedule->interval, s.interval);
    pacing = std::max(pacing, planned[i].pacing);
  }
  if (members.size() > 1) schedule->tailMs = tailsMs;
  return FramePlan::Deformable{first.priority, schedule, pacing};
}

// What the groups served after each are expected to need (infinite while one of their bodies
// has not been measured: then the shares are equal); one more entry, 0, after the last.
std::vector<double> laterFloorsMs(const std::vector<std::vector<int>>& groups,
                                  const std::vector<FramePlan::Deformable>& planned) {
  std::vector<double> later(groups.size() + 1, 0.0);
  for (size_t n = groups.size(); n-- > 0;) {
    later[n] = later[n + 1];
    for (int i : groups[n]) {
      const double expected = planned[i].schedule->expectedMs;
      later[n] += expected < 0.0 ? std::numeric_limits<double>::infinity() : FramePlan::kMargin * expected;
    }
  }
  return later;
}

// The time left after the deformables is the room a lower interval would take from the fluids;
// read only when some interval could come down.
double slackAfterDeformables(const std::vector<FramePlan::Deformable>& planned, const Deadline& frame) {
  const bool anyRaised = std::any_of(planned.begin(), planned.end(),
                                     [](const FramePlan::Deformable& d) { return d.schedule->interval > 1; });
  return frame.unlimited() || !anyRaised ? std::numeric_limits<double>::infinity() : frame.remainingMs();
}

}  // namespace

bool World::stepDeformables(double dt, const Deadline& frame, StepStats* stats) {
  DeformableFrame d = planDeformables(dt, frame, stats->stepIndex);
  const FrameContacts contacts = findFrameContacts(d, dt, frame, stats);
  stepContactGroups(d, contacts, frame);
  std::vector<double> steppedDt;
  for (const ActorStats& a : d.actors) steppedDt.push_back(a.simulatedDt);
  settlePairContacts(contacts.pairs, d.bodies, steppedDt);
  const std::vector<bool> missed = finishDeformableSteps(d, frame, stats);
  stats->actors.insert(stats->actors.end(), d.actors.begin(), d.actors.end());
  if (!FramePlan::adjustIntervals(d.planned, missed, slackAfterDeformables(d.planned, frame)))
    stats->budgetInfeasible = true;
  return std::find(missed.begin(), missed.end(), true) == missed.end();
}

World::DeformableFrame World::planDeformables(double dt, const Deadline& frame, uint64_t stepIndex) {
  DeformableFrame d;
  d.handles = deformableHandles();
  const int count = static_cast<int>(d.handles.size());
  // Where the dynamic rigid bodies and the deformables can go before a deformable at the
  // highest interval would step again.
  const double lookahead = FramePlan::kMaxInterval * dt;
  const std::vector<Filtered<Aabb>> rigidReach =
      frame.unlimited() ? std::vector<Filtered<Aabb>>{} : dynamicBodiesReach(lookahead);
  std::vector<int> priorities;
  for (int i = 0; i < count; ++i) {
    const DeformableHandle h = d.handles[static_cast<size_t>(i)];
    DeformableBody& body = *deformable(h);
    ActorSchedule& s = body.schedule();
    s.pendingDt += dt;
    if (s.ownRateFrames > 0) --s.ownRateFrames;
    const int priority = body.desc().priority;
    FramePlan::Deformable planned{priority, &s};
    if (!frame.unlimited()) planned = pacedDeformable(planned, body, rigidReach, lookahead);
    if (frame.unlimited() || !planned.ownRate()) s.interval = 1;  // no budget: nothing lowers a rate
    d.bodies.push_back(&body);
    d.planned.push_back(planned);
    priorities.push_back(priority);
    d.due.push_back(FramePlan::due(stepIndex, i, count, planned));
    d.actors.push_back(actorStats(ActorKind::Deformable, h.index1, h.generation, priority, 0.0));
    // Paced by liquids, the frames its step spans.
    d.actors.back().interval = planned.pacing == FramePlan::Pacing::WithLiquids ? s.waitedFrames + 1 : s.interval;
  }
  for (int i : FramePlan::byPriority(priorities))
    if (d.due[i]) d.served.push_back(i);
  d.deadlines.resize(d.handles.size());
  return d;
}

FramePlan::Deformable World::pacedDeformable(FramePlan::Deformable planned, const DeformableBody& body,
                                             const std::vector<Filtered<Aabb>>& rigidReach, double lookahead) const {
  if (!rigidReach.empty() && withinReach(body, rigidReach, lookahead)) {
    planned.pacing = FramePlan::Pacing::EveryFrame;
    return planned;
  }
  if (planned.schedule->ownRateFrames > 0) return planned;
  const Aabb bounds = body.bounds();
  fluids_.forEach([&](FluidHandle, const FluidActor& fluid) {
    if (!weighsOn(fluid, bounds, body.desc().filter)) return;
    planned.pacing = FramePlan::Pacing::WithLiquids;
    planned.liquidSteps += fluid.stepCount();
  });
  return planned;
}

void World::stepContactGroups(DeformableFrame& d, const FrameContacts& contacts, const Deadline& frame) {
  const std::vector<Filtered<ContactCollider>> colliders = deformableContactColliders(colliders_);
  const std::vector<std::vector<int>>& groups = contacts.groups;
  const std::vector<double> laterMs = laterFloorsMs(groups, d.planned);
  // Side by side, each group takes the rest of the frame (and its own floor) for itself.
  const int count = static_cast<int>(groups.size());
  const bool concurrent = runsConcurrently(count);
  runActors(*tasks_, concurrent, count, [&](int n) {
    const std::vector<int>& members = groups[static_cast<size_t>(n)];
    ActorSchedule schedule;
    const FramePlan::Deformable group = groupAsOne(d.planned, members, &schedule);
    const FramePlan::DeformableDeadlines deadlines = FramePlan::deformableDeadlines(
        frame, schedule, concurrent ? 0.0 : laterMs[static_cast<size_t>(n) + 1], fluidsExpectedMs(group.priority),
        concurrent ? 1 : count - n, group.ownRate());
    stepGroupWithin(d, members, contacts, colliders, deadlines, frame);
  });
}

void World::stepGroupWithin(DeformableFrame& d, const std::vector<int>& members, const FrameContacts& contacts,
                            const std::vector<Filtered<ContactCollider>>& colliders,
                            const FramePlan::DeformableDeadlines& deadlines, const Deadline& frame) {
  const double start = frame.elapsedMs();
  double mark = start;
  std::vector<DeformableStepInput> inputs(members.size());
  for (size_t m = 0; m < members.size(); ++m) {
    const int i = members[m];
    d.deadlines[i] = deadlines;
    DeformableStepInput& input = inputs[m];
    input = frameStepInput(d.handles, i, colliders, contacts);
    input.deadline = deadlines.share;
    input.floorDeadline = deadlines.floor;
    if (fluids_.size() > 0) {  // a world without fluids pays nothing for them
      setFluidLoads(d.handles[i], *d.bodies[i]);
      d.bodies[i]->applyFluidLoads(config_.gravity);
      const double now = frame.elapsedMs();
      d.actors[i].phase(Phase::Coupling).ms += now - mark;
      mark = now;
    }
  }
  stepGroup(d, members, inputs);
  // A group's time is its members' by their share of its nodes (what each adds to the solve).
  double groupNodes = 0.0;
  for (int i : members) groupNodes += d.bodies[i]->nodeCount();
  const double ms = frame.elapsedMs() - start;
  for (size_t m = 0; m < members.size(); ++m) {
    ActorStats& a = d.actors[members[m]];
    a.totalMs = ms * d.bodies[members[m]]->nodeCount() / groupNodes;
    a.simulatedDt = inputs[m].dt;
  }
}

std::vector<bool> World::finishDeformableSteps(DeformableFrame& d, const Deadline& frame, StepStats* stats) {
  std::vector<bool> missed(d.handles.size(), false);
  for (size_t i = 0; i < d.handles.size(); ++i) {
    ActorSchedule& s = *d.planned[i].schedule;
    ActorStats& a = d.actors[i];
    if (!d.due[i]) {
      ++s.waitedFrames;
      continue;
    }
    a.completedStep = true;
    contactEvents_.update(d.handles[i].index1, d.handles[i].generation, *d.bodies[i]);
    pushDynamicColliders(*d.bodies[i]);
    a.slices = 1 + a.phase(Phase::Solve).iterations;
    stats->maxSliceMs = std::max(stats->maxSliceMs, longestDeformableSliceMs(a));
    missed[i] = a.floorMissed;
    if (d.deadlines[i].forced && frame.expired()) stats->budgetInfeasible = true;
    if (a.diverged) {
      log(LogLevel::Warning, "deformable (%u, %u) diverged; restored its previous state", a.index1, a.generation);
      FramePlan::noteDiverged(s);
    }
    s.expectedMs = FramePlan::smoothed(s.expectedMs, a.totalMs);
    s.tailMs = FramePlan::smoothed(s.tailMs, a.phase(Phase::Contacts).ms + a.phase(Phase::Embed).ms);
    s.pendingDt = 0.0;
    s.waitedFrames = 0;
    if (d.planned[i].pacing == FramePlan::Pacing::WithLiquids) s.liquidSteps = d.planned[i].liquidSteps;
  }
  return missed;
}

template <class FilteredColliders>
DeformableStepInput World::deformableStepInput(const DeformableBody& body, const FilteredColliders& colliders) const {
  DeformableStepInput input;
  input.gravity = config_.gravity;
  input.tasks = tasks_.get();
  input.colliders = meeting(colliders, body.desc().filter);
  input.collider = [this](uint32_t index1, uint32_t generation) -> const Collider* {
    return colliders_.get(index1, generation);
  };
  return input;
}

void World::pushDynamicColliders(const DeformableBody& body) {
  for (const ContactReaction& r : body.contactReactions()) {
    Collider* c = colliders_.get(r.colliderIndex1, r.colliderGeneration);
    if (!c || c->bodyType() != BodyType::Dynamic) continue;
    c->addContactImpulse(r.impulse, r.point);
  }
}

Status World::solveDeformableStatic(DeformableHandle handle, int32_t maxIterations, double tolerance,
                                    StaticSolveResult* result) {
  DeformableBody* body = deformable(handle);
  if (!body) return fail(Status::InvalidId, "deformable: no such deformable in this world");
  return solveStaticEquilibrium(*body, deformableStepInput(*body, deformableContactColliders(colliders_)),
                                maxIterations, tolerance, result);
}

std::vector<RigidContactBody> World::rigidContactBodies() const {
  std::vector<RigidContactBody> rigids;
  colliders_.forEach([&](ColliderHandle h, const Collider& c) {
    RigidContactBody r;
    if (!c.geometry() || !c.massProperties(&r.mass, &r.inertia)) return;
    r.id = PairBodyId{h.index1, h.generation, 1};
    r.geometry = c.geometry();
    const Pose pose = c.pose();
    r.centre = pose.position;
    r.rotation = pose.rotation.toRotationMatrix();
    r.linearVelocity = c.linearVelocity();
    r.angularVelocity = c.angularVelocity();
    r.velocityChange = c.lastStepVelocityChange();
    r.spinChange = c.lastStepSpinChange();
    r.filter = c.filter();
    r.frictionCoefficient = c.desc().friction;
    rigids.push_back(r);
  });
  return rigids;
}

void World::addAttachmentSprings(const std::vector<DeformableHandle>& handles, const std::vector<bool>& touchesRigid,
                                 const std::vector<RigidContactBody>& rigids, std::vector<PairContact>* pairs) const {
  const int32_t rigidBase = static_cast<int32_t>(handles.size());
  // An attached node does not also touch the body it is attached to, as a held node's collider
  // contacts ignore its collider; nor does that body's corner touch a triangle at the node.
  pairs->erase(std::remove_if(pairs->begin(), pairs->end(), [&](const PairContact& p) {
    if (p.rigidSide)
      return deformable(handles[p.nodeBody])->attachedTo(p.node, p.triangleBodyId.index1, p.triangleBodyId.generation);
    if (!p.rigidNode) return false;
    const DeformableBody& body = *deformable(handles[p.triangleBody]);
    return std::any_of(p.triangleNodes.begin(), p.triangleNodes.end(),
                       [&](int32_t n) { return body.attachedTo(n, p.nodeBodyId.index1, p.nodeBodyId.generation); });
  }), pairs->end());
  for (size_t i = 0; i < handles.size(); ++i)
    if (touchesRigid[i])
      deformable(handles[i])->attachmentSprings(static_cast<int32_t>(i), rigids, rigidBase, pairs);
}

std::vector<PairContact> World::findDeformablePairContacts(const std::vector<DeformableHandle>& handles,
                                                          const std::vector<bool>& touchesRigid,
                                                          const std::vector<RigidContactBody>& rigids, double dt,
                                                          const Deadline& frame, StepStats* stats) {
  const double start = frame.elapsedMs();
  std::vector<PairContactBody> bodies;
  for (size_t i = 0; i < handles.size(); ++i) {
    bodies.push_back(deformable(handles[i])->pairContactBody(dt));
    bodies.back().id = PairBodyId{handles[i].index1, handles[i].generation};
    bodies.back().touchesRigid = touchesRigid[i];
  }
  std::vector<PairContact> pairs;
  findPairContacts(bodies, rigids, dt, *tasks_, &pairs);
  // One slice: the deformables' steps read every contact.
  stats->deformableContactMs = frame.elapsedMs() - start;
  stats->maxSliceMs = std::max(stats->maxSliceMs, stats->deformableContactMs);
  stats->deformablePairContacts = static_cast<int>(pairs.size());
  return pairs;
}

void World::stepGroup(DeformableFrame& d, const std::vector<int>& members,
                      const std::vector<DeformableStepInput>& inputs) {
  try {
    if (members.size() == 1) {
      d.bodies[members[0]]->step(inputs[0], &d.actors[members[0]]);
      return;
    }
    std::vector<PhaseTimer> timers;
    timers.reserve(members.size());
    std::vector<ContactGroupMember> group;
    for (size_t m = 0; m < members.size(); ++m) {
      timers.emplace_back(inputs[m].deadline, &d.actors[members[m]]);
      group.push_back({d.bodies[members[m]], &inputs[m], &timers.back(), &d.actors[members[m]]});
    }
    stepContactGroup(group);
  } catch (const std::bad_alloc&) {
    for (int i : members) d.bodies[i]->abandonStep();
    actorOutOfMemory_ = true;
  }
}

World::FrameContacts World::findFrameContacts(const DeformableFrame& d, double dt, const Deadline& frame,
                                              StepStats* stats) {
  FrameContacts contacts;
  const size_t count = d.handles.size();
  std::vector<ContactGroupCandidate> candidates(count);
  // A body solves with the dynamic bodies it touches when it steps this frame's dt on the CPU
  // (Bullet steps them by dt); otherwise they are colliders with its contacts' reactions.
  contacts.touchesRigid.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const DeformableBody& body = *d.bodies[i];
    candidates[i] =
        ContactGroupCandidate{static_cast<bool>(d.due[i]), !body.solvesOnDevice(), d.planned[i].schedule->pendingDt};
    contacts.touchesRigid[i] = candidates[i].steps && candidates[i].onCpu && candidates[i].dt == dt;
  }
  if (std::find(contacts.touchesRigid.begin(), contacts.touchesRigid.end(), true) != contacts.touchesRigid.end())
    contacts.rigids = rigidContactBodies();
  contacts.pairs = findDeformablePairContacts(d.handles, contacts.touchesRigid, contacts.rigids, dt, frame, stats);
  addAttachmentSprings(d.handles, contacts.touchesRigid, contacts.rigids, &contacts.pairs);
  candidates.resize(count + contacts.rigids.size(), ContactGroupCandidate{true, true, dt});
  contacts.groups = formContactGroups(d.served, candidates, &contacts.pairs);
  return contacts;
}

DeformableStepInput World::frameStepInput(const std::vector<DeformableHandle>& handles, int i,
                                          const std::vector<Filtered<ContactCollider>>& colliders,
                                          const FrameContacts& contacts) const {
  DeformableBody& body = *deformable(handles[static_cast<size_t>(i)]);
  DeformableStepInput input = deformableStepInput(body, colliders);
  input.dt = body.schedule().pendingDt;
  input.pairContacts = &contacts.pairs;
  input.pairBody = i;
  if (!contacts.touchesRigid[static_cast<size_t>(i)]) return input;
  // Its own contacts do not meet the dynamic bodies it solves with: its pair contacts hold those.
  const std::vector<RigidContactBody>& rigids = contacts.rigids;
  auto solvedWith = [&](const ContactCollider& c) { return findRigidBody(rigids, c.index1, c.generation) != nullptr; };
  input.colliders.erase(std::remove_if(input.colliders.begin(), input.colliders.end(), solvedWith),
                        input.colliders.end());
  input.rigidBodies = &rigids;
  input.rigidBodyBase = static_cast<int32_t>(handles.size());
  return input;
}

std::vector<Filtered<Aabb>> World::dynamicBodiesReach(double lookahead) const {
  std::vector<Filtered<Aabb>> reach;
  colliders_.forEach([&](ColliderHandle, const Collider& c) {
    if (c.bodyType() != BodyType::Dynamic || !c.geometry()) return;
    const PreparedCollider& g = *c.geometry();
    // Its speed, and what gravity adds (a ball at the top of its bounce is coming back).
    const double travel = lookahead * (c.linearVelocity().norm() + c.angularVelocity().norm() * g.boundRadius) +
                          0.5 * config_.gravity.norm() * lookahead * lookahead;
    reach.push_back({c.filter(), Aabb{g.bounds.lo - Vec3::Constant(travel), g.bounds.hi + Vec3::Constant(travel)}});
  });
  return reach;
}

}  // namespace vp

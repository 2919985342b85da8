#include "world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <system_error>

#include "core/allocator.h"
#include "core/log.h"
#include "core/parallel_for.h"
#include "core/run_delay.h"
#include "deform/contact_group_solve.h"
#include "deform/contact_groups.h"
#include "deform/pair_contact_settlement.h"
#include "gpu_kernels/device_query.h"

namespace vp {

Status validateGravity(const Vec3& g) {
  if (!g.allFinite() || g.norm() > 1e4)
    return fail(Status::InvalidArgument, "gravity = (%g, %g, %g): must be finite with magnitude <= 1e4", g.x(), g.y(),
                g.z());
  return Status::Ok;
}

Status validateFrameBudget(double ms) {
  if (!(ms >= 0.0 && ms <= 1e4))
    return fail(Status::InvalidArgument, "frameBudgetMs = %g: must be in [0, 1e4] (0 = unlimited)", ms);
  return Status::Ok;
}

Status validateWorldConfig(const WorldConfig& c) {
  VP_TRY(validateGravity(c.gravity));
  VP_TRY(validateFrameBudget(c.frameBudgetMs));
  if (c.workerCount < 1 || c.workerCount > 64)
    return fail(Status::InvalidArgument, "workerCount = %d: must be in [1, 64]", c.workerCount);
  if (!(c.rigidMaxSubstep >= 1e-5 && c.rigidMaxSubstep <= 1.0))
    return fail(Status::InvalidArgument, "rigidMaxSubstep = %g: must be in [1e-5, 1] seconds", c.rigidMaxSubstep);
  if ((c.tasks.enqueue == nullptr) != (c.tasks.finish == nullptr))
    return fail(Status::InvalidArgument, "enqueueTask and finishTask: set both or neither");
  const int device = static_cast<int>(c.device);
  if (device < static_cast<int>(ComputeDevice::Auto) || device > static_cast<int>(ComputeDevice::Cuda))
    return fail(Status::InvalidArgument, "device = %d: must be a vpDevice (0 Auto, 1 Cpu, 2 Cuda)", device);
  if (c.device == ComputeDevice::Cuda && gpu::cudaDeviceCount() == 0)
    return fail(Status::Unsupported, "device = 2 (Cuda): no usable CUDA device (this build %s the CUDA path)",
                gpu::cudaCompiled() ? "has" : "lacks");
  return Status::Ok;
}

World::World(const WorldConfig& config)
    : config_(config),
      tasks_(TaskSystem::create(config.tasks, config.workerCount)),
      collision_(config.gravity),
      deformablesOnDevice_(config.device != ComputeDevice::Cpu && gpu::cudaDeviceCount() > 0) {
  colliders_.setGenerationLimit(kHandleGenerationLimit);
  deformables_.setGenerationLimit(kHandleGenerationLimit);
  fluids_.setGenerationLimit(kHandleGenerationLimit);
}

static_assert(World::kHandleGenerationLimit <= kDeformableSolidBit,
              "a deformable's generation with kDeformableSolidBit set must not be a collider's");

Status World::create(const WorldConfig& config, std::unique_ptr<World>* out) {
  VP_TRY(validateWorldConfig(config));
  const uint64_t refusals = hostAllocationRefusals();
  std::unique_ptr<World> world;
  try {
    world.reset(new World(config));
  } catch (const std::system_error& e) {
    return fail(Status::OutOfMemory, "workerCount = %d: cannot start the worker threads (%s)", config.workerCount,
                e.what());
  }
  if (hostAllocationRefusals() != refusals)
    return fail(Status::OutOfMemory, "the host allocator refused memory the rigid-body world needs");
  *out = std::move(world);
  log(LogLevel::Info, "world created: %d worker(s)%s, frame budget %g ms", config.workerCount,
      config.tasks.enqueue ? " (host task system)" : "", config.frameBudgetMs);
  return Status::Ok;
}

World::~World() {
  colliders_.forEach([this](ColliderHandle, Collider& c) { collision_.remove(c); });
}

Status World::createCollider(ColliderDesc desc, ColliderHandle* out) {
  VP_TRY(validateColliderDesc(desc));
  const uint64_t refusals = hostAllocationRefusals();
  const ColliderHandle h = colliders_.insert(std::make_unique<Collider>(std::move(desc)));
  Collider& c = *collider(h);
  try {
    collision_.add(c);
  } catch (...) {
    colliders_.remove(h.index1, h.generation);
    throw;
  }
  if (hostAllocationRefusals() != refusals) {
    collision_.remove(c);
    colliders_.remove(h.index1, h.generation);
    return fail(Status::OutOfMemory, "the host allocator refused memory the collider's rigid body needs");
  }
  *out = h;
  return Status::Ok;
}

Status World::destroyCollider(ColliderHandle handle) {
  std::unique_ptr<Collider> c = colliders_.remove(handle.index1, handle.generation);
  if (!c) return fail(Status::InvalidId, "collider id (%u, %u) is stale or null", handle.index1, handle.generation);
  collision_.remove(*c);
  deformables_.forEach([&](DeformableHandle, DeformableBody& d) { d.detachAll(handle.index1, handle.generation); });
  return Status::Ok;
}

Status World::createDeformable(DeformableDesc desc, DeformableHandle* out) {
  std::unique_ptr<DeformableBody> body;
  VP_TRY(DeformableBody::create(std::move(desc), &body));
  if (deformablesOnDevice_ && !ok(body->setSolveOnDevice(true)))
    log(LogLevel::Warning, "deformable '%s' solves on the CPU: %s", body->desc().name.c_str(), lastError());
  *out = deformables_.insert(std::move(body));
  return Status::Ok;
}

Status World::destroyDeformable(DeformableHandle handle) {
  std::unique_ptr<DeformableBody> body = deformables_.remove(handle.index1, handle.generation);
  if (!body)
    return fail(Status::InvalidId, "deformable id (%u, %u) is stale or null", handle.index1, handle.generation);
  contactEvents_.forget(handle.index1, handle.generation);
  return Status::Ok;
}

Status World::createFluid(FluidDesc desc, FluidHandle* out) {
  std::unique_ptr<FluidActor> fluid;
  VP_TRY(FluidActor::create(std::move(desc), *tasks_, &fluid));
  *out = fluids_.insert(std::move(fluid));
  return Status::Ok;
}

Status World::destroyFluid(FluidHandle handle) {
  std::unique_ptr<FluidActor> fluid = fluids_.remove(handle.index1, handle.generation);
  if (!fluid) return fail(Status::InvalidId, "fluid id (%u, %u) is stale or null", handle.index1, handle.generation);
  return Status::Ok;
}

namespace {

// The first actor phase of the frame that failed, as "fluid (1, 1): phase 9" (vpPhase numbers).
bool describeFailedPhase(const StepStats& stats, std::string* what) {
  for (const ActorStats& a : stats.actors)
    for (int p = 0; p < kPhaseCount; ++p)
      if (a.phases[p].failed) {
        const char* kind = a.kind == ActorKind::Fluid ? "fluid" : a.kind == ActorKind::Deformable ? "deformable" : "rigid";
        *what = std::string(kind) + " (" + std::to_string(a.index1) + ", " + std::to_string(a.generation) +
                "): phase " + std::to_string(p);
        return true;
      }
  return false;
}

// Handles of every object in slot order, and the first one with a given name (scene files
// name objects; names need not be unique).
template <class T>
std::vector<typename SlotMap<T>::Handle> handlesOf(const SlotMap<T>& map) {
  std::vector<typename SlotMap<T>::Handle> handles;
  handles.reserve(map.size());
  map.forEach([&](typename SlotMap<T>::Handle h, const T&) { handles.push_back(h); });
  return handles;
}

template <class T>
bool findByName(const SlotMap<T>& map, const std::string& name, typename SlotMap<T>::Handle* out) {
  bool found = false;
  map.forEach([&](typename SlotMap<T>::Handle h, const T& object) {
    if (!found && object.desc().name == name) *out = h, found = true;
  });
  return found;
}

}  // namespace

std::vector<FluidHandle> World::fluidHandles() const { return handlesOf(fluids_); }
bool World::findFluid(const std::string& name, FluidHandle* out) const { return findByName(fluids_, name, out); }
std::vector<DeformableHandle> World::deformableHandles() const { return handlesOf(deformables_); }
bool World::findDeformable(const std::string& name, DeformableHandle* out) const {
  return findByName(deformables_, name, out);
}
std::vector<ColliderHandle> World::colliderHandles() const { return handlesOf(colliders_); }
bool World::findCollider(const std::string& name, ColliderHandle* out) const {
  return findByName(colliders_, name, out);
}
bool World::colliderHandleOf(const Collider* collider, ColliderHandle* out) const {
  bool found = false;
  colliders_.forEach([&](ColliderHandle h, const Collider& c) {
    if (&c == collider) *out = h, found = true;
  });
  return found;
}

Status World::setGravity(const Vec3& gravity) {
  VP_TRY(validateGravity(gravity));
  config_.gravity = gravity;
  collision_.setGravity(gravity);
  return Status::Ok;
}

Status World::setFrameBudget(double frameBudgetMs) {
  VP_TRY(validateFrameBudget(frameBudgetMs));
  config_.frameBudgetMs = frameBudgetMs;
  return Status::Ok;
}

Status World::step(double dt) {
  if (!(dt > 0.0 && dt <= 1.0)) return fail(Status::InvalidArgument, "dt = %g: must be in (0, 1] seconds", dt);
  const Deadline frame(config_.clock, config_.frameBudgetMs);
  StepStats stats;
  stats.stepIndex = stats_.stepIndex + 1;
  stats.dt = dt;
  stats.budgetMs = config_.frameBudgetMs;
  stats.colliderCount = static_cast<int>(colliders_.size());
  const double runDelayAtStart = poolRunDelayMs();
  actorOutOfMemory_ = false;
  contactEvents_.beginFrame();
  stepRigidBodies(dt, frame, &stats);
  const bool floorsHeld = stepDeformables(dt, frame, &stats);
  stepFluids(dt, frame, floorsHeld, &stats);
  finishStats(frame, &stats);
  balanceWorkers(frame, runDelayAtStart);
  stats_ = std::move(stats);
  if (actorOutOfMemory_)
    return fail(Status::OutOfMemory, "out of memory: an actor's step was undone (the others stepped); the world "
                                     "can be stepped again");
  std::string failed;
  if (describeFailedPhase(stats_, &failed))
    return fail(Status::PhaseFailed, "%s failed (vpActorStats.failedPhases; the log says why); the step completed "
                "the rest and the world can be stepped again", failed.c_str());
  return Status::Ok;
}

double World::poolRunDelayMs() const {
  const double workers = tasks_->workerRunDelayMs();
  const double caller = threadRunDelayMs();
  return workers < 0.0 || caller < 0.0 ? -1.0 : workers + caller;
}

void World::balanceWorkers(const Deadline& frame, double runDelayAtStart) {
  if (runDelayAtStart < 0.0) return;  // no statistics: the workers stay on
  const double delay = poolRunDelayMs();
  const bool used = tasks_->workerCount() > 1;
  const bool on = contention_.noteFrame(frame.elapsedMs(), delay < 0.0 ? -1.0 : delay - runDelayAtStart, used);
  if (on != used) {
    log(LogLevel::Debug, "worker threads %s", on ? "back on (probe)" : "off: the cores are busy with other work");
    tasks_->setWorkersEnabled(on);
  }
}

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

// Whether a fluid reaches a body within `bounds` and sees it (it then takes it as a solid).
bool reaches(const FluidActor& fluid, const Aabb& bounds, const CollisionFilter& filter) {
  return fluid.domainBounds().overlaps(bounds) && fluid.desc().filter.meets(filter);
}

// Whether a liquid's weight acts on such a body: a two-way liquid that reaches it.
bool weighsOn(const FluidActor& fluid, const Aabb& bounds, const CollisionFilter& filter) {
  return fluid.desc().kind == FluidKind::Liquid && fluid.desc().twoWayCoupling && reaches(fluid, bounds, filter);
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

// The colliders an actor with `filter` meets, in the list's order.
template <class Entry>
std::vector<Entry> meeting(const std::vector<Filtered<Entry>>& colliders, const CollisionFilter& filter) {
  std::vector<Entry> out;
  out.reserve(colliders.size());
  for (const Filtered<Entry>& c : colliders)
    if (c.filter.meets(filter)) out.push_back(c.entry);
  return out;
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

}  // namespace

bool World::runsConcurrently(int actors) const {
  // An injected clock is read on the stepping thread only, in plan order: its readings, and
  // so every budget decision, are then the same for any worker count (vpClockFn).
  if (config_.clock.now) return false;
  const int workers = tasks_->workerCount();
  return workers > 1 && actors > 1 && actors <= workers;
}

template <class Work>
void World::runActors(bool concurrent, int count, const Work& work) {
  if (!concurrent) {
    for (int n = 0; n < count; ++n) work(n);
    return;
  }
  // One actor per item; the pool runs each actor's own parallel loops inline (task_system.h).
  parallelFor(*tasks_, count, 1, [&](int64_t begin, int64_t end) {
    for (int64_t n = begin; n < end; ++n) work(static_cast<int>(n));
  });
}

ActorStats World::actorStats(ActorKind kind, uint32_t index1, uint32_t generation, int priority, double dt) const {
  ActorStats a;
  a.kind = kind;
  a.index1 = index1;
  a.generation = generation;
  a.priority = priority;
  a.simulatedDt = dt;
  return a;
}

// Bullet's step is not budgeted (it is cheap and must stay consistent); its cost is what the
// plan measures before sharing out the rest of the frame.
void World::stepRigidBodies(double dt, const Deadline& frame, StepStats* stats) {
  ActorStats rigid = actorStats(ActorKind::Rigid, 0, 0, 0, dt);
  const double start = frame.elapsedMs();
  std::vector<Collider*> kinematics, loaded;
  colliders_.forEach([&](ColliderHandle, Collider& c) {
    if (c.bodyType() == BodyType::Kinematic) kinematics.push_back(&c);
    if (c.hasHostLoad() || c.hasContactLoad()) loaded.push_back(&c);
  });
  // The loads of each fluid's last completed step; those of several fluids on one body add
  // up, in the fluids' slot order; a body destroyed since is skipped.
  auto forEachFluidLoad = [&](const auto& visit) {
    fluids_.forEach([&](FluidHandle, const FluidActor& fluid) {
      for (const FluidColliderLoad& l : fluid.loads())
        if (Collider* c = colliders_.get(l.index1, l.generation); c != nullptr) visit(*c, l);
    });
  };
  // And the weight of each liquid that reaches a dynamic body, on the body where it is now.
  struct Hydrostatic {
    Collider* collider;
    PressureLoad load;
  };
  std::vector<Hydrostatic> hydrostatics;
  if (fluids_.size() > 0)
    colliders_.forEach([&](ColliderHandle, Collider& c) {
      if (c.bodyType() != BodyType::Dynamic || !c.geometry()) return;
      fluids_.forEach([&](FluidHandle, const FluidActor& fluid) {
        if (weighsOn(fluid, c.geometry()->bounds, c.filter()))
          hydrostatics.push_back({&c, fluid.hydrostaticColliderLoad(config_.gravity, *c.geometry())});
      });
    });
  forEachFluidLoad([&](Collider& c, const FluidColliderLoad&) { loaded.push_back(&c); });
  for (const Hydrostatic& h : hydrostatics) loaded.push_back(h.collider);
  std::sort(loaded.begin(), loaded.end());
  loaded.erase(std::unique(loaded.begin(), loaded.end()), loaded.end());
  for (Collider* c : loaded) c->clearFluidLoad();
  forEachFluidLoad([](Collider& c, const FluidColliderLoad& l) {
    c.addFluidLoad(l.load.force, l.load.torque, l.load.addedMass, l.seen);
  });
  for (const Hydrostatic& h : hydrostatics) h.collider->addHydrostaticLoad(h.load.force, h.load.torque);
  colliders_.forEach([](ColliderHandle, Collider& c) { c.trackVelocity(); });
  for (Collider* c : loaded) {
    c->prepareFluidLoad(config_.gravity);
    c->prepareContactLoad(dt);  // the deformables' pushes of the last frame
  }
  const uint64_t refusals = hostAllocationRefusals();
  const CollisionWorld::StepResult result = collision_.step(dt, config_.rigidMaxSubstep, kinematics.data(),
                                                            static_cast<int>(kinematics.size()), loaded.data(),
                                                            static_cast<int>(loaded.size()));
  stats->rigidSubsteps = result.substeps;
  if (const uint64_t refused = hostAllocationRefusals() - refusals)
    log(LogLevel::Warning, "the host allocator refused %llu block(s) Bullet needed in this step; they came from the "
                           "system heap", static_cast<unsigned long long>(refused));
  rigid.diverged = result.restoredBodies > 0;
  if (result.energyBlewUp)
    log(LogLevel::Warning, "rigid step blew up: the dynamic bodies' energy rose %g J beyond the %g J its work "
        "explains (kinetic %g -> %g)", StepEnergyGuard::unexplainedGain(result.energy),
        result.energy.gravityWork + result.energy.appliedWork + result.energy.boundedWork, result.energy.kineticStart,
        result.energy.kineticEnd);
  if (rigid.diverged)
    log(LogLevel::Warning, "%d rigid bod%s diverged; restored to their state before the step", result.restoredBodies,
        result.restoredBodies == 1 ? "y" : "ies");
  for (Collider* c : loaded) {
    c->clearFluidLoad();
    c->clearHostLoad();
    c->clearContactLoad();
  }
  colliders_.forEach([](ColliderHandle, Collider& c) { c.syncGeometry(); });
  rigid.phase(Phase::Rigid).ms = frame.elapsedMs() - start;
  rigid.totalMs = rigid.phase(Phase::Rigid).ms;
  rigid.slices = 1;
  rigid.completedStep = true;
  stats->maxSliceMs = std::max(stats->maxSliceMs, rigid.totalMs);
  stats->actors.push_back(rigid);
}

double World::fluidsExpectedMs(int priority) {
  double ms = 0.0;
  fluids_.forEach([&](FluidHandle, FluidActor& fluid) {
    if (fluid.desc().priority >= priority) ms += FramePlan::kMargin * std::max(fluid.schedule().expectedMs, 0.0);
  });
  return ms;
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

void World::stepGroup(const std::vector<DeformableHandle>& handles, const std::vector<int>& members,
                      const std::vector<DeformableStepInput>& inputs, ActorStats* actors) {
  try {
    if (members.size() == 1) {
      deformable(handles[members[0]])->step(inputs[0], &actors[members[0]]);
      return;
    }
    std::vector<PhaseTimer> timers;
    timers.reserve(members.size());
    std::vector<ContactGroupMember> group;
    for (size_t m = 0; m < members.size(); ++m) {
      timers.emplace_back(inputs[m].deadline, &actors[members[m]]);
      group.push_back({deformable(handles[members[m]]), &inputs[m], &timers.back(), &actors[members[m]]});
    }
    stepContactGroup(group);
  } catch (const std::bad_alloc&) {
    for (int i : members) deformable(handles[i])->abandonStep();
    actorOutOfMemory_ = true;
  }
}

World::FrameContacts World::findFrameContacts(const std::vector<DeformableHandle>& handles,
                                              const std::vector<int>& served, const std::vector<bool>& due,
                                              double dt, const Deadline& frame, StepStats* stats) {
  FrameContacts contacts;
  std::vector<ContactGroupCandidate> candidates(handles.size());
  // A body solves with the dynamic bodies it touches when it steps this frame's dt on the CPU
  // (Bullet steps them by dt); otherwise they are colliders with its contacts' reactions.
  contacts.touchesRigid.resize(handles.size());
  for (size_t i = 0; i < handles.size(); ++i) {
    DeformableBody& body = *deformable(handles[i]);
    candidates[i] = ContactGroupCandidate{static_cast<bool>(due[i]), !body.solvesOnDevice(), body.schedule().pendingDt};
    contacts.touchesRigid[i] = candidates[i].steps && candidates[i].onCpu && candidates[i].dt == dt;
  }
  if (std::find(contacts.touchesRigid.begin(), contacts.touchesRigid.end(), true) != contacts.touchesRigid.end())
    contacts.rigids = rigidContactBodies();
  contacts.pairs = findDeformablePairContacts(handles, contacts.touchesRigid, contacts.rigids, dt, frame, stats);
  addAttachmentSprings(handles, contacts.touchesRigid, contacts.rigids, &contacts.pairs);
  candidates.resize(handles.size() + contacts.rigids.size(), ContactGroupCandidate{true, true, dt});
  contacts.groups = formContactGroups(served, candidates, &contacts.pairs);
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

bool World::stepDeformables(double dt, const Deadline& frame, StepStats* stats) {
  const std::vector<Filtered<ContactCollider>> contactColliders = deformableContactColliders(colliders_);
  const std::vector<DeformableHandle> handles = deformableHandles();
  std::vector<FramePlan::Deformable> planned;
  std::vector<int> priorities;
  std::vector<bool> due;
  // Where the dynamic rigid bodies and the deformables can go before a deformable at the
  // highest interval would step again.
  const double lookahead = FramePlan::kMaxInterval * dt;
  const std::vector<Filtered<Aabb>> rigidReach =
      frame.unlimited() ? std::vector<Filtered<Aabb>>{} : dynamicBodiesReach(lookahead);
  for (size_t i = 0; i < handles.size(); ++i) {
    DeformableBody& body = *deformable(handles[i]);
    ActorSchedule& s = body.schedule();
    s.pendingDt += dt;
    const bool held = !rigidReach.empty() && withinReach(body, rigidReach, lookahead);
    if (frame.unlimited() || held) s.interval = 1;  // no budget: nothing lowers a rate
    planned.push_back(FramePlan::Deformable{body.desc().priority, &s, held});
    priorities.push_back(body.desc().priority);
    due.push_back(FramePlan::due(stats->stepIndex, static_cast<int>(i), static_cast<int>(handles.size()), s));
  }
  // Served by priority, the due ones.
  std::vector<int> served;
  for (int i : FramePlan::byPriority(priorities))
    if (due[i]) served.push_back(i);
  std::vector<ActorStats> actors(handles.size());
  std::vector<FramePlan::DeformableDeadlines> deadlines(handles.size());
  for (size_t i = 0; i < handles.size(); ++i) {
    actors[i] = actorStats(ActorKind::Deformable, handles[i].index1, handles[i].generation, priorities[i], 0.0);
    actors[i].interval = planned[i].schedule->interval;
  }
  const FrameContacts contacts = findFrameContacts(handles, served, due, dt, frame, stats);
  const std::vector<std::vector<int>>& groups = contacts.groups;
  // What the groups served after each are expected to need (infinite while one of their
  // bodies has not been measured: then the shares are equal).
  std::vector<double> laterFloorsMs(groups.size() + 1, 0.0);
  for (size_t n = groups.size(); n-- > 0;) {
    laterFloorsMs[n] = laterFloorsMs[n + 1];
    for (int i : groups[n]) {
      const double expected = planned[i].schedule->expectedMs;
      laterFloorsMs[n] += expected < 0.0 ? std::numeric_limits<double>::infinity() : FramePlan::kMargin * expected;
    }
  }
  // Side by side, each group takes the rest of the frame (and its own floor) for itself.
  const bool concurrent = runsConcurrently(static_cast<int>(groups.size()));
  runActors(concurrent, static_cast<int>(groups.size()), [&](int n) {
    const std::vector<int>& members = groups[static_cast<size_t>(n)];
    const int first = members.front();
    // The group is planned as one actor: the first member's priority, every member's tail.
    ActorSchedule schedule = deformable(handles[first])->schedule();
    double tailsMs = 0.0;
    bool held = false;
    for (int i : members) {
      const ActorSchedule& s = deformable(handles[i])->schedule();
      tailsMs += std::max(s.tailMs, 0.0);
      schedule.interval = std::max(schedule.interval, s.interval);
      held = held || planned[i].heldEveryFrame;
    }
    if (members.size() > 1) schedule.tailMs = tailsMs;
    const FramePlan::DeformableDeadlines groupDeadlines = FramePlan::deformableDeadlines(
        frame, schedule, concurrent ? 0.0 : laterFloorsMs[n + 1], fluidsExpectedMs(priorities[first]),
        concurrent ? 1 : static_cast<int>(groups.size()) - n, held);
    const double start = frame.elapsedMs();
    double mark = start;
    std::vector<DeformableStepInput> inputs(members.size());
    for (size_t m = 0; m < members.size(); ++m) {
      const int i = members[m];
      DeformableBody& body = *deformable(handles[i]);
      deadlines[i] = groupDeadlines;
      DeformableStepInput& input = inputs[m];
      input = frameStepInput(handles, i, contactColliders, contacts);
      input.deadline = groupDeadlines.share;
      input.floorDeadline = groupDeadlines.floor;
      if (fluids_.size() > 0) {  // a world without fluids pays nothing for them
        setFluidLoads(handles[i], body);
        body.applyFluidLoads(config_.gravity);
        const double now = frame.elapsedMs();
        actors[i].phase(Phase::Coupling).ms += now - mark;
        mark = now;
      }
    }
    stepGroup(handles, members, inputs, actors.data());
    // A group's time is its members' by their share of its nodes (what each adds to the solve).
    double groupNodes = 0.0;
    for (int i : members) groupNodes += deformable(handles[i])->nodeCount();
    const double ms = frame.elapsedMs() - start;
    for (size_t m = 0; m < members.size(); ++m) {
      ActorStats& a = actors[members[m]];
      a.totalMs = ms * deformable(handles[members[m]])->nodeCount() / groupNodes;
      a.simulatedDt = inputs[m].dt;
    }
  });
  std::vector<DeformableBody*> bodies;
  std::vector<double> steppedDt;
  for (size_t i = 0; i < handles.size(); ++i) {
    bodies.push_back(deformable(handles[i]));
    steppedDt.push_back(actors[i].simulatedDt);
  }
  settlePairContacts(contacts.pairs, bodies, steppedDt);
  std::vector<bool> missed(handles.size(), false);
  for (size_t i = 0; i < handles.size(); ++i) {
    ActorSchedule& s = *planned[i].schedule;
    ActorStats& a = actors[i];
    if (!due[i]) {
      ++s.waitedFrames;
      continue;
    }
    a.completedStep = true;
    contactEvents_.update(handles[i].index1, handles[i].generation, *deformable(handles[i]));
    pushDynamicColliders(*deformable(handles[i]));
    a.slices = 1 + a.phase(Phase::Solve).iterations;
    stats->maxSliceMs = std::max(stats->maxSliceMs, longestDeformableSliceMs(a));
    missed[i] = a.floorMissed;
    if (deadlines[i].forced && frame.expired()) stats->budgetInfeasible = true;
    if (a.diverged) {
      log(LogLevel::Warning, "deformable (%u, %u) diverged; restored its previous state", a.index1, a.generation);
      FramePlan::noteDiverged(s);
    }
    s.expectedMs = FramePlan::smoothed(s.expectedMs, a.totalMs);
    s.tailMs = FramePlan::smoothed(s.tailMs, a.phase(Phase::Contacts).ms + a.phase(Phase::Embed).ms);
    s.pendingDt = 0.0;
    s.waitedFrames = 0;
  }
  stats->actors.insert(stats->actors.end(), actors.begin(), actors.end());
  // The time left after the deformables is the room a lower interval would take from the
  // fluids; read only when some interval could come down.
  const bool anyRaised = std::any_of(planned.begin(), planned.end(),
                                     [](const FramePlan::Deformable& d) { return d.schedule->interval > 1; });
  const double slackMs =
      frame.unlimited() || !anyRaised ? std::numeric_limits<double>::infinity() : frame.remainingMs();
  if (!FramePlan::adjustIntervals(planned, missed, slackMs)) stats->budgetInfeasible = true;
  return std::find(missed.begin(), missed.end(), true) == missed.end();
}

std::vector<Filtered<FluidCollider>> World::fluidSolids(const Deadline& frame, StepStats* stats) {
  std::vector<Filtered<FluidCollider>> solids;
  if (fluids_.size() == 0) return solids;
  colliders_.forEach([&](ColliderHandle h, const Collider& c) {
    if (c.geometry())
      solids.push_back({c.filter(), FluidCollider{h.index1, h.generation, c.geometry(), c.sharedGeometry(),
                                                  c.bodyType() == BodyType::Dynamic,
                                                  SolidMotion{c.linearVelocity(), c.angularVelocity()}}});
  });
  // A deformable that no fluid both reaches and sees is left out rather than kept up to date
  // for nothing.
  deformables_.forEach([&](DeformableHandle h, DeformableBody& body) {
    const Aabb bounds = body.bounds();
    bool seen = false;
    fluids_.forEach([&](FluidHandle, const FluidActor& f) { seen = seen || reaches(f, bounds, body.desc().filter); });
    if (!seen) return;
    // The surface's refresh is the deformable's coupling work, and one slice of the frame.
    const double start = frame.elapsedMs();
    std::shared_ptr<const PreparedCollider> surface = body.fluidSurface();
    const double ms = frame.elapsedMs() - start;
    stats->maxSliceMs = std::max(stats->maxSliceMs, ms);
    for (ActorStats& a : stats->actors)
      if (a.kind == ActorKind::Deformable && a.index1 == h.index1 && a.generation == h.generation) {
        a.phase(Phase::Coupling).ms += ms;
        a.totalMs += ms;
      }
    solids.push_back({body.desc().filter, FluidCollider{h.index1, h.generation | kDeformableSolidBit, surface.get(),
                                                        surface, true, body.rigidMotion()}});
  });
  return solids;
}

void World::setFluidLoads(DeformableHandle handle, DeformableBody& body) const {
  FluidImmersion& immersion = body.immersion();
  immersion.clearLoads();
  const Aabb bounds = body.bounds();
  Array<Eigen::Vector3d> vertices;  // the surface now, once some liquid weighs on it
  fluids_.forEach([&](FluidHandle, const FluidActor& fluid) {
    // The hydrostatic part holds as soon as the liquid reaches the body, whether or not a step
    // of it has completed since (a body falling in meets the liquid at once).
    if (weighsOn(fluid, bounds, body.desc().filter)) {
      if (vertices.empty()) vertices = immersion.vertices(body.positions());
      Array<Vec3> hydrostatic;
      fluid.hydrostaticSurfaceLoad(*tasks_, config_.gravity, vertices, immersion.triangles(), &hydrostatic);
      immersion.addHydrostaticLoad(hydrostatic);
    }
    for (const FluidColliderLoad& l : fluid.loads())
      if (l.index1 == handle.index1 && l.generation == (handle.generation | kDeformableSolidBit))
        immersion.addLoad(l.vertexForces, l.load.addedMass, l.seen);
  });
}

void World::stepFluids(double dt, const Deadline& frame, bool floorsHeld, StepStats* stats) {
  const std::vector<Filtered<FluidCollider>> colliders = fluidSolids(frame, stats);
  const std::vector<FluidHandle> handles = fluidHandles();
  std::vector<int> priorities;
  for (FluidHandle h : handles) priorities.push_back(fluid(h)->desc().priority);
  std::vector<ActorStats> actors(handles.size());
  std::vector<SliceBudget> budgets(handles.size());
  // No time for the fluids when the frame is spent, or when a deformable ended above its
  // floor (the floors come first); a fluid then runs only what its rate cap forces.
  const bool noTime = !frame.unlimited() && (!floorsHeld || frame.remainingMs() <= 0.0);
  std::vector<int> served;  // by priority
  for (int i : FramePlan::byPriority(priorities)) {
    FluidActor& f = *fluid(handles[i]);
    ActorSchedule& s = f.schedule();
    s.pendingDt += dt;
    actors[i] = actorStats(ActorKind::Fluid, handles[i].index1, handles[i].generation, priorities[i], 0.0);
    actors[i].interval = s.interval;
    actors[i].progress = f.progress();
    FramePlan::Fluid planned{priorities[i], &s, f.stepWork().expected(), f.stepInProgress() ? f.stepWork().done() : 0};
    budgets[i].minWork = FramePlan::fluidMinWork(planned);
    budgets[i].targetSliceMs = FramePlan::targetSliceMs(stats->budgetMs);
    ++s.stepFrames;
    if (noTime && budgets[i].minWork == 0) continue;  // its step waits for the next frame
    served.push_back(i);
  }
  const bool concurrent = runsConcurrently(static_cast<int>(served.size()));
  runActors(concurrent, static_cast<int>(served.size()), [&](int n) {
    const int i = served[static_cast<size_t>(n)];
    FluidActor& f = *fluid(handles[i]);
    ActorSchedule& s = f.schedule();
    SliceBudget& budget = budgets[i];
    if (noTime) {
      budget.share = frame.within(0.0);
    } else if (!frame.unlimited()) {
      // Side by side, each has the rest of the frame; in turn, its share of what is left.
      int equals = 0;
      bool lowerAfter = false;
      for (size_t m = static_cast<size_t>(n); m < served.size(); ++m) {
        equals += priorities[served[m]] == priorities[i];
        lowerAfter = lowerAfter || priorities[served[m]] < priorities[i];
      }
      budget.share = concurrent ? frame.share(1.0) : FramePlan::fluidShare(frame, s, equals, lowerAfter);
    }
    FluidStepInput input;  // read only when a step begins
    if (!f.stepInProgress()) {
      input.dt = s.pendingDt;
      input.gravity = config_.gravity;
      input.tasks = tasks_.get();
      input.colliders = meeting(colliders, f.desc().filter);
      s.pendingDt = 0.0;
      s.stepMs = 0.0;
    }
    ActorStats& a = actors[i];
    const double start = frame.elapsedMs();
    try {
      f.advance(input, budget, &a);
    } catch (const std::bad_alloc&) {
      f.abandonStep();
      actorOutOfMemory_ = true;
    }
    a.totalMs = frame.elapsedMs() - start;
  });
  for (int i : served) {
    FluidActor& f = *fluid(handles[i]);
    ActorSchedule& s = f.schedule();
    ActorStats& a = actors[i];
    stats->maxSliceMs = std::max(stats->maxSliceMs, f.maxSliceMs());
    if (budgets[i].minWork > 0 && a.slices > 0 && (frame.expired() || !floorsHeld)) stats->budgetInfeasible = true;
    s.stepMs += a.totalMs;
    if (a.completedStep) {
      noteFluidStepCompleted(s);
      if (a.diverged) log(LogLevel::Warning, "fluid (%u, %u) diverged; restored its last completed step", a.index1, a.generation);
    } else {
      a.simulatedDt = 0.0;
    }
    a.interval = s.interval;
  }
  stats->actors.insert(stats->actors.end(), actors.begin(), actors.end());
}

void World::noteFluidStepCompleted(ActorSchedule& s) {
  // Frames since the last completed step, the waiting ones included.
  s.interval = std::max(s.stepFrames, 1);
  s.stepFrames = 0;
  s.expectedMs = FramePlan::smoothed(s.expectedMs, s.stepMs);
}

void World::finishStats(const Deadline& frame, StepStats* stats) {
  stats->totalMs = frame.elapsedMs();
  if (stats->budgetMs > 0.0) stats->overBudgetMs = std::max(0.0, stats->totalMs - stats->budgetMs);
  for (const ActorStats& a : stats->actors) {
    for (const PhaseStats& p : a.phases) stats->budgetCut = stats->budgetCut || p.budgetCut;
    if (a.kind == ActorKind::Fluid) stats->fluidInterval = std::max(stats->fluidInterval, a.interval);
  }
}

}  // namespace vp

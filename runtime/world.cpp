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
#include "gpu_kernels/device_query.h"
#include "world_stages.h"

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

// What a rigid step's guards did, and the blocks Bullet took from the system heap because the
// host's allocator refused them.
void logRigidStep(const CollisionWorld::StepResult& result, uint64_t allocationRefusals) {
  if (allocationRefusals > 0)
    log(LogLevel::Warning, "the host allocator refused %llu block(s) Bullet needed in this step; they came from the "
                           "system heap", static_cast<unsigned long long>(allocationRefusals));
  if (result.energyBlewUp)
    log(LogLevel::Warning, "rigid step blew up: the dynamic bodies' energy rose %g J beyond the %g J its work "
        "explains (kinetic %g -> %g)", StepEnergyGuard::unexplainedGain(result.energy),
        result.energy.gravityWork + result.energy.appliedWork + result.energy.boundedWork, result.energy.kineticStart,
        result.energy.kineticEnd);
  if (result.restoredBodies > 0)
    log(LogLevel::Warning, "%d rigid bod%s diverged; restored to their state before the step", result.restoredBodies,
        result.restoredBodies == 1 ? "y" : "ies");
}

}  // namespace

bool World::runsConcurrently(int actors) const {
  // An injected clock is read on the stepping thread only, in plan order: its readings, and
  // so every budget decision, are then the same for any worker count (vpClockFn).
  if (config_.clock.now) return false;
  const int workers = tasks_->workerCount();
  return workers > 1 && actors > 1 && actors <= workers;
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
  std::vector<Collider*> kinematics;
  colliders_.forEach([&](ColliderHandle, Collider& c) {
    if (c.bodyType() == BodyType::Kinematic) kinematics.push_back(&c);
  });
  const std::vector<Collider*> loaded = prepareRigidLoads(dt);
  const uint64_t refusals = hostAllocationRefusals();
  const CollisionWorld::StepResult result = collision_.step(dt, config_.rigidMaxSubstep, kinematics.data(),
                                                            static_cast<int>(kinematics.size()), loaded.data(),
                                                            static_cast<int>(loaded.size()));
  logRigidStep(result, hostAllocationRefusals() - refusals);
  stats->rigidSubsteps = result.substeps;
  rigid.diverged = result.restoredBodies > 0;
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

std::vector<Collider*> World::prepareRigidLoads(double dt) {
  std::vector<Collider*> loaded;
  colliders_.forEach([&](ColliderHandle, Collider& c) {
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
    c.addFluidLoad(l.load.force, l.load.torque, l.load.addedMass, l.seen, l.rigidDrag);
  });
  for (const Hydrostatic& h : hydrostatics) h.collider->addHydrostaticLoad(h.load.force, h.load.torque);
  colliders_.forEach([](ColliderHandle, Collider& c) { c.trackVelocity(); });
  for (Collider* c : loaded) {
    c->prepareContactLoad(dt);  // the deformables' pushes of the last frame
    c->prepareFluidLoad(config_.gravity, dt);
  }
  return loaded;
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

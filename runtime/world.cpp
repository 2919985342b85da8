#include "world.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/log.h"

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
  return Status::Ok;
}

World::World(const WorldConfig& config)
    : config_(config), tasks_(TaskSystem::create(config.tasks, config.workerCount)), collision_(config.gravity) {}

Status World::create(const WorldConfig& config, std::unique_ptr<World>* out) {
  VP_TRY(validateWorldConfig(config));
  out->reset(new World(config));
  log(LogLevel::Info, "world created: %d worker(s)%s, frame budget %g ms", config.workerCount,
      config.tasks.enqueue ? " (host task system)" : "", config.frameBudgetMs);
  return Status::Ok;
}

World::~World() {
  colliders_.forEach([this](ColliderHandle, Collider& c) { collision_.remove(c); });
}

Status World::createCollider(ColliderDesc desc, ColliderHandle* out) {
  VP_TRY(validateColliderDesc(desc));
  auto collider = std::make_unique<Collider>(std::move(desc));
  collision_.add(*collider);
  *out = colliders_.insert(std::move(collider));
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
  *out = deformables_.insert(std::move(body));
  return Status::Ok;
}

Status World::destroyDeformable(DeformableHandle handle) {
  std::unique_ptr<DeformableBody> body = deformables_.remove(handle.index1, handle.generation);
  if (!body)
    return fail(Status::InvalidId, "deformable id (%u, %u) is stale or null", handle.index1, handle.generation);
  deformableExpectedMs_.erase(body.get());
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
  fluidBacklog_.erase(fluid.get());
  return Status::Ok;
}

namespace {

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
  stepping_.store(true, std::memory_order_release);
  const Deadline frame(config_.clock, config_.frameBudgetMs);

  StepStats stats;
  stats.stepIndex = stats_.stepIndex + 1;
  stats.dt = dt;
  stats.budgetMs = config_.frameBudgetMs;
  stats.colliderCount = static_cast<int>(colliders_.size());

  // Phase 1: rigid bodies. Bullet's step is not budgeted (it is cheap and must stay
  // consistent); the budget is spent by the iterative solvers of the actors that follow.
  ActorStats rigid;
  rigid.kind = ActorKind::Rigid;
  rigid.simulatedDt = dt;
  {
    const double start = frame.elapsedMs();
    std::vector<Collider*> kinematics, loaded;
    colliders_.forEach([&](ColliderHandle, Collider& c) {
      if (c.bodyType() == BodyType::Kinematic) kinematics.push_back(&c);
    });
    // Loads of several fluids on one body add up; a body destroyed since is skipped.
    // In the fluids' slot order, so the sums do not depend on the backlog map's order.
    auto forEachFluidLoad = [&](const auto& visit) {
      fluids_.forEach([&](FluidHandle, const FluidActor& fluid) {
        if (const auto it = fluidBacklog_.find(&fluid); it != fluidBacklog_.end())
          for (const FluidColliderLoad& l : it->second.loads)
            if (Collider* c = colliders_.get(l.index1, l.generation); c != nullptr) visit(*c, l.load);
      });
    };
    forEachFluidLoad([&](Collider& c, const PressureLoad&) {
      c.clearFluidLoad();
      loaded.push_back(&c);
    });
    std::sort(loaded.begin(), loaded.end());
    loaded.erase(std::unique(loaded.begin(), loaded.end()), loaded.end());
    forEachFluidLoad([](Collider& c, const PressureLoad& l) { c.addFluidLoad(l.force, l.torque, l.addedMass); });
    colliders_.forEach([](ColliderHandle, Collider& c) { c.trackVelocity(); });
    for (Collider* c : loaded) c->prepareFluidLoad(dt, config_.gravity);
    stats.rigidSubsteps = collision_.step(dt, config_.rigidMaxSubstep, kinematics.data(),
                                          static_cast<int>(kinematics.size()), loaded.data(),
                                          static_cast<int>(loaded.size()));
    for (Collider* c : loaded) c->clearFluidLoad();
    rigid.phase(Phase::Rigid).ms = frame.elapsedMs() - start;
    rigid.totalMs = rigid.phase(Phase::Rigid).ms;
  }
  stats.actors.push_back(rigid);
  colliders_.forEach([](ColliderHandle, Collider& c) { c.syncGeometry(); });
  std::vector<ContactCollider> contactColliders;
  colliders_.forEach([&](ColliderHandle, const Collider& c) {
    if (c.geometry()) contactColliders.push_back(ContactCollider{c.geometry(), c.desc().friction});
  });

  // Phase 3: deformables, then fluids. Budget policy: the fluids due this frame are decided
  // first (fluid pacing, fluid_pacing.h: a fluid not due keeps its time for later and its
  // last loads). Their expected step time (each fluid's smoothed measured cost) is held back
  // from the deformables, which run in slot order, each with an equal share of what is left
  // of the frame before that reserve when its turn comes, or more: all of it but the smoothed
  // step time of the deformables after it, when those are cheap; then the due fluids run, each
  // with an equal share of what is left. Time one actor does not use passes on to the next.
  int dueFluids = 0;
  double reserveMs = 0.0;
  {
    int ordinal = 0;
    fluids_.forEach([&](FluidHandle, FluidActor& fluid) {
      FluidBacklog& backlog = fluidBacklog_[&fluid];
      backlog.pendingDt += dt;
      backlog.due = fluidPacing_.due(stats.stepIndex, ordinal++, static_cast<int>(fluids_.size()), backlog.waitedFrames);
      if (backlog.due) {
        ++dueFluids;
        reserveMs += FluidPacing::kReserveMargin * std::max(backlog.expectedStepMs, 0.0);
      }
    });
  }
  // Runs one actor's step and records its stats.
  auto runActor = [&](ActorKind kind, uint32_t index1, uint32_t generation, const auto& stepActor) {
    ActorStats a;
    a.kind = kind;
    a.index1 = index1;
    a.generation = generation;
    a.simulatedDt = dt;
    const double start = frame.elapsedMs();
    stepActor(&a);
    a.totalMs = frame.elapsedMs() - start;
    if (a.diverged)
      log(LogLevel::Warning, "%s (%u, %u) diverged; %s", kind == ActorKind::Fluid ? "fluid" : "deformable", index1,
          generation, kind == ActorKind::Fluid ? "its flow was reset to rest" : "restored its previous state");
    stats.actors.push_back(a);
  };
  int deformablesLeft = static_cast<int>(deformables_.size());
  // laterMs[i]: what the deformables after the i-th are expected to need (infinite while one of
  // them has not been measured: then the shares are equal).
  std::vector<double> laterMs(deformables_.size() + 1, 0.0);
  {
    std::vector<double> expected;
    deformables_.forEach([&](DeformableHandle, DeformableBody& body) {
      expected.push_back(deformableExpectedMs_.try_emplace(&body, -1.0).first->second);
    });
    for (size_t i = expected.size(); i-- > 0;)
      laterMs[i] = laterMs[i + 1] + (expected[i] < 0.0 ? std::numeric_limits<double>::infinity()
                                                        : FluidPacing::kReserveMargin * expected[i]);
  }
  size_t deformableIndex = 0;
  deformables_.forEach([&](DeformableHandle h, DeformableBody& body) {
    double& expectedMs = deformableExpectedMs_[&body];
    const double laterDeformablesMs = laterMs[++deformableIndex];
    const Deadline share = frame.shareLeaving(1.0 / deformablesLeft--, reserveMs, laterDeformablesMs);
    runActor(ActorKind::Deformable, h.index1, h.generation, [&](ActorStats* a) {
      DeformableStepInput input;
      input.dt = dt;
      input.gravity = config_.gravity;
      input.deadline = share;
      input.tasks = tasks_.get();
      input.colliders = contactColliders;
      input.collider = [this](uint32_t index1, uint32_t generation) -> const Collider* {
        return colliders_.get(index1, generation);
      };
      body.step(input, a);
    });
    expectedMs = FluidPacing::smoothed(expectedMs, stats.actors.back().totalMs);
  });

  std::vector<FluidCollider> fluidColliders;
  if (fluids_.size() > 0)
    colliders_.forEach([&](ColliderHandle h, const Collider& c) {
      if (c.geometry())
        fluidColliders.push_back(FluidCollider{h.index1, h.generation, c.geometry(), c.bodyType() == BodyType::Dynamic});
    });
  double fluidStepsMs = 0.0;
  int fluidsLeft = dueFluids;
  fluids_.forEach([&](FluidHandle h, FluidActor& fluid) {
    FluidBacklog& backlog = fluidBacklog_[&fluid];
    if (!backlog.due) {
      ++backlog.waitedFrames;
      ActorStats deferred;
      deferred.kind = ActorKind::Fluid;
      deferred.index1 = h.index1;
      deferred.generation = h.generation;
      deferred.simulatedDt = 0.0;
      stats.actors.push_back(deferred);
      return;
    }
    const Deadline share = frame.share(1.0 / fluidsLeft--);
    runActor(ActorKind::Fluid, h.index1, h.generation, [&](ActorStats* a) {
      FluidStepInput input;
      input.dt = backlog.pendingDt;
      input.gravity = config_.gravity;
      input.deadline = share;
      input.tasks = tasks_.get();
      input.colliders = fluidColliders;
      backlog.loads.clear();
      fluid.step(input, a, &backlog.loads);
      a->simulatedDt = input.dt;
    });
    const double stepMs = stats.actors.back().totalMs;
    fluidStepsMs += stepMs;
    backlog.expectedStepMs = FluidPacing::smoothed(backlog.expectedStepMs, stepMs);
    backlog.pendingDt = 0.0;
    backlog.waitedFrames = 0;
  });

  stats.totalMs = frame.elapsedMs();
  // The deformables' iterative solves take whatever share they are given (and a cut solve
  // catches up later), so they are not part of the cost the fluids must fit beside; a fluid
  // step cannot be cut. The fluids' rate therefore comes before the solves' accuracy.
  double elasticMs = 0.0;
  for (const ActorStats& a : stats.actors)
    if (a.kind == ActorKind::Deformable) elasticMs += a.phase(Phase::Solve).ms;
  double everyFluidMs = 0.0;
  for (const auto& [fluid, backlog] : fluidBacklog_) everyFluidMs += std::max(backlog.expectedStepMs, 0.0);
  fluidPacing_.observe(config_.frameBudgetMs, stats.totalMs - fluidStepsMs - elasticMs, everyFluidMs);
  stats.fluidInterval = fluidPacing_.interval();
  for (const ActorStats& a : stats.actors)
    for (const PhaseStats& p : a.phases) stats.budgetCut = stats.budgetCut || p.budgetCut;
  stats_ = std::move(stats);
  stepping_.store(false, std::memory_order_release);
  return Status::Ok;
}

}  // namespace vp

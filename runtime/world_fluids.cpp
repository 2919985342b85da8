// The fluids' stage of a world step (frame_plan.h has the policy): what they see as solids,
// their shares of the frame, their slices run, then the plan's bookkeeping; and what the
// deformables read of them (their loads).
#include <algorithm>
#include <new>

#include "core/log.h"
#include "world.h"
#include "world_stages.h"

namespace vp {

// The fluids of one frame, by handle order.
struct World::FluidFrame {
  std::vector<FluidHandle> handles;
  std::vector<FluidActor*> fluids;
  std::vector<int> priorities;
  std::vector<ActorStats> actors;
  std::vector<SliceBudget> budgets;
  std::vector<int> served;  // those that run this frame, by priority
  bool noTime = false;      // a served fluid runs only what its rate cap forces
};

namespace {

// The share of the frame of the n-th served fluid: side by side, each has the rest of the
// frame; in turn, its share of what is left.
Deadline fluidShare(const std::vector<int>& priorities, const std::vector<int>& served, size_t n,
                    const ActorSchedule& s, bool concurrent, const Deadline& frame) {
  if (concurrent) return frame.share(1.0);
  const int priority = priorities[served[n]];
  int equals = 0;
  bool lowerAfter = false;
  for (size_t m = n; m < served.size(); ++m) {
    equals += priorities[served[m]] == priority;
    lowerAfter = lowerAfter || priorities[served[m]] < priority;
  }
  return FramePlan::fluidShare(frame, s, equals, lowerAfter);
}

}  // namespace

void World::stepFluids(double dt, const Deadline& frame, bool floorsHeld, StepStats* stats) {
  const std::vector<Filtered<FluidCollider>> solids = fluidSolids(frame, stats);
  FluidFrame f = planFluids(dt, frame, floorsHeld, stats->budgetMs);
  advanceFluids(f, solids, frame);
  finishFluidSteps(f, frame, floorsHeld, stats);
}

std::vector<Filtered<FluidCollider>> World::fluidSolids(const Deadline& frame, StepStats* stats) {
  std::vector<Filtered<FluidCollider>> solids;
  if (fluids_.size() == 0) return solids;
  colliders_.forEach([&](ColliderHandle h, const Collider& c) {
    if (!c.geometry()) return;
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

World::FluidFrame World::planFluids(double dt, const Deadline& frame, bool floorsHeld, double budgetMs) {
  FluidFrame f;
  f.handles = fluidHandles();
  for (FluidHandle h : f.handles) {
    f.fluids.push_back(fluid(h));
    f.priorities.push_back(f.fluids.back()->desc().priority);
  }
  f.actors.resize(f.handles.size());
  f.budgets.resize(f.handles.size());
  // No time for the fluids when the frame is spent, or when a deformable ended above its
  // floor (the floors come first).
  f.noTime = !frame.unlimited() && (!floorsHeld || frame.remainingMs() <= 0.0);
  for (int i : FramePlan::byPriority(f.priorities)) {
    const FluidActor& fluid = *f.fluids[i];
    ActorSchedule& s = f.fluids[i]->schedule();
    s.pendingDt += dt;
    ActorStats& a = f.actors[i];
    a = actorStats(ActorKind::Fluid, f.handles[i].index1, f.handles[i].generation, f.priorities[i], 0.0);
    a.interval = s.interval;
    a.progress = fluid.progress();
    const FramePlan::Fluid planned{f.priorities[i], &s, fluid.stepWork().expected(),
                                   fluid.stepInProgress() ? fluid.stepWork().done() : 0};
    f.budgets[i].minWork = FramePlan::fluidMinWork(planned);
    f.budgets[i].targetSliceMs = FramePlan::targetSliceMs(budgetMs);
    ++s.stepFrames;
    if (f.noTime && f.budgets[i].minWork == 0) continue;  // its step waits for the next frame
    f.served.push_back(i);
  }
  return f;
}

void World::advanceFluids(FluidFrame& f, const std::vector<Filtered<FluidCollider>>& solids, const Deadline& frame) {
  const bool concurrent = runsConcurrently(static_cast<int>(f.served.size()));
  runActors(*tasks_, concurrent, static_cast<int>(f.served.size()), [&](int n) {
    const int i = f.served[static_cast<size_t>(n)];
    FluidActor& fluid = *f.fluids[i];
    ActorSchedule& s = fluid.schedule();
    SliceBudget& budget = f.budgets[i];
    if (f.noTime)
      budget.share = frame.within(0.0);
    else if (!frame.unlimited())
      budget.share = fluidShare(f.priorities, f.served, static_cast<size_t>(n), s, concurrent, frame);
    FluidStepInput input;  // read only when a step begins
    if (!fluid.stepInProgress()) {
      input.dt = s.pendingDt;
      input.gravity = config_.gravity;
      input.tasks = tasks_.get();
      input.colliders = meeting(solids, fluid.desc().filter);
      s.pendingDt = 0.0;
      s.stepMs = 0.0;
    }
    ActorStats& a = f.actors[i];
    const double start = frame.elapsedMs();
    try {
      fluid.advance(input, budget, &a);
    } catch (const std::bad_alloc&) {
      fluid.abandonStep();
      actorOutOfMemory_ = true;
    }
    a.totalMs = frame.elapsedMs() - start;
  });
}

void World::finishFluidSteps(FluidFrame& f, const Deadline& frame, bool floorsHeld, StepStats* stats) {
  for (int i : f.served) {
    const FluidActor& fluid = *f.fluids[i];
    ActorSchedule& s = f.fluids[i]->schedule();
    ActorStats& a = f.actors[i];
    stats->maxSliceMs = std::max(stats->maxSliceMs, fluid.maxSliceMs());
    if (f.budgets[i].minWork > 0 && a.slices > 0 && (frame.expired() || !floorsHeld)) stats->budgetInfeasible = true;
    s.stepMs += a.totalMs;
    if (a.completedStep) {
      noteFluidStepCompleted(s);
      if (a.diverged)
        log(LogLevel::Warning, "fluid (%u, %u) diverged; restored its last completed step", a.index1, a.generation);
    } else {
      a.simulatedDt = 0.0;
    }
    a.interval = s.interval;
  }
  stats->actors.insert(stats->actors.end(), f.actors.begin(), f.actors.end());
}

void World::noteFluidStepCompleted(ActorSchedule& s) {
  // Frames since the last completed step, the waiting ones included.
  s.interval = std::max(s.stepFrames, 1);
  s.stepFrames = 0;
  s.expectedMs = FramePlan::smoothed(s.expectedMs, s.stepMs);
}

double World::fluidsExpectedMs(int priority) {
  double ms = 0.0;
  fluids_.forEach([&](FluidHandle, FluidActor& fluid) {
    if (fluid.desc().priority >= priority) ms += FramePlan::kMargin * std::max(fluid.schedule().expectedMs, 0.0);
  });
  return ms;
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
        immersion.addLoad(l.vertexForces, l.load.addedMass, l.seen, l.drag);
  });
}

}  // namespace vp

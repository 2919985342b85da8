// Fluid actor step (see fluid_actor.h).
#include "fluid/fluid_actor.h"

#include <algorithm>
#include <cmath>

#include "core/log.h"
#include "core/parallel_for.h"
#include "fluid/fluid_sources.h"

namespace vp {

Status FluidActor::create(FluidDesc desc, TaskSystem& tasks, std::unique_ptr<FluidActor>* out) {
  VP_TRY(validateFluidDesc(desc));
  if (desc.kind == FluidKind::Liquid)
    return fail(Status::Unsupported, "kind = 1 (liquid): liquids are not available in this build yet");
  std::unique_ptr<FluidActor> actor(new FluidActor(std::move(desc)));
  VP_TRY(initMacGrid(actor->desc_.grid, actor->desc_.sides, &actor->grid_));
  VP_TRY(initFaceFractionField(actor->desc_.grid, &actor->fractions_));
  const size_t cells = static_cast<size_t>(actor->grid_.cellCount());
  actor->smokeDensity_.assign(cells, 0.0);
  actor->temperature_.assign(cells, actor->desc_.smoke.ambientTemperature);
  (void)tasks;
  *out = std::move(actor);
  return Status::Ok;
}

double FluidActor::totalSmoke() const {
  double sum = 0.0;
  for (double d : smokeDensity_) sum += d;
  return sum * grid_.spec.h * grid_.spec.h * grid_.spec.h;
}

double FluidActor::liquidVolume() const { return 0.0; }

const FluidSurface& FluidActor::surface() {
  if (surfaceStep_ != stepCount_) {
    surface_ = FluidSurface{};
    surfaceStep_ = stepCount_;
  }
  return surface_;
}

Status FluidActor::updateFractions(const std::vector<FluidCollider>& colliders) {
  std::vector<const PreparedCollider*> geometry;
  std::vector<ColliderSnapshot> now;
  for (const FluidCollider& c : colliders) {
    if (c.geometry == nullptr) continue;
    geometry.push_back(c.geometry);
    const ColliderShape& s = c.geometry->shape;
    now.push_back(ColliderSnapshot{c.index1, c.generation, c.geometry->bounds, s.rotation, s.translation,
                                   s.linearVelocity, s.angularVelocity});
  }
  const int count = static_cast<int>(geometry.size());
  bool sameSet = fractionsValid_ && now.size() == snapshots_.size();
  for (size_t i = 0; sameSet && i < now.size(); ++i)
    sameSet = now[i].index1 == snapshots_[i].index1 && now[i].generation == snapshots_[i].generation;
  if (!sameSet) {
    // A collider came or went: a full recompute is simpler than tracking the union of
    // everything that changed, and it happens only on such events.
    VP_TRY(computeFaceFractions(geometry.data(), count, &fractions_));
  } else {
    for (size_t i = 0; i < now.size(); ++i) {
      const ColliderSnapshot& a = snapshots_[i];
      const ColliderSnapshot& b = now[i];
      const bool moved = a.translation != b.translation || a.rotation.coeffs() != b.rotation.coeffs() ||
                         a.linearVelocity != b.linearVelocity || a.angularVelocity != b.angularVelocity;
      if (moved) VP_TRY(updateFaceFractions(geometry.data(), count, a.bounds, b.bounds, &fractions_));
    }
  }
  snapshots_ = std::move(now);
  fractionsValid_ = true;
  return Status::Ok;
}

double FluidActor::maxSpeed(TaskSystem& tasks) const {
  double speed = 0.0;
  for (int a = 0; a < 3; ++a) {
    const std::vector<double>& u = grid_.velocity[a];
    struct Max {
      double v = 0.0;
      Max& operator+=(const Max& o) { v = std::max(v, o.v); return *this; }
    };
    const Max m = parallelReduce<Max>(tasks, static_cast<int64_t>(u.size()), 1 << 15, [&](int64_t b, int64_t e) {
      Max r;
      for (int64_t f = b; f < e; ++f) r.v = std::max(r.v, std::abs(u[static_cast<size_t>(f)]));
      return r;
    });
    // Per component: the speed bound |u| <= sqrt(3) max component is not worth its sqrt.
    speed = std::max(speed, m.v);
  }
  return speed;
}

void FluidActor::step(const FluidStepInput& input, ActorStats* stats, std::vector<FluidColliderLoad>* loads) {
  TaskSystem& tasks = *input.tasks;
  ++stepCount_;
  const double dt = input.dt;
  const Deadline& deadline = input.deadline;
  const FluidSolverSettings& solver = desc_.solver;
  const MacGridSpec& s = grid_.spec;

  double t0 = deadline.elapsedMs();
  if (Status st = updateFractions(input.colliders); st != Status::Ok)
    log(LogLevel::Error, "fluid '%s': face fractions failed: %s", desc_.name.c_str(), lastError());
  stats->phase(Phase::Fractions).ms += deadline.elapsedMs() - t0;

  double speed = maxSpeed(tasks);
  for (const FluidCollider& c : input.colliders)
    if (c.geometry != nullptr && c.geometry->bounds.overlaps(Aabb{s.origin, s.origin + s.h * Eigen::Vector3d(s.nx, s.ny, s.nz)}))
      speed = std::max(speed, c.geometry->shape.linearVelocity.norm() +
                                  c.geometry->shape.angularVelocity.norm() * c.geometry->boundRadius);
  const int substeps = std::clamp(static_cast<int>(std::ceil(speed * dt / (solver.cflNumber * s.h))), 1,
                                  solver.maxSubsteps);
  const double h = dt / substeps;

  std::vector<PressureLoad> loadSum(input.colliders.size());
  PressureSolveSettings pressureSettings;
  pressureSettings.tolerance = solver.pressureTolerance;
  pressureSettings.maxIterations = solver.pressureMaxIterations;
  PhaseStats& pressurePhase = stats->phase(Phase::Pressure);
  for (int sub = 0; sub < substeps; ++sub) {
    t0 = deadline.elapsedMs();
    advectVelocity(tasks, grid_, h, solver.advection, advection_);
    std::vector<double>* scalars[2] = {&smokeDensity_, &temperature_};
    advectCellScalars(tasks, grid_, h, solver.advection, scalars, 2, advection_);
    stats->phase(Phase::Advect).ms += deadline.elapsedMs() - t0;

    t0 = deadline.elapsedMs();
    applySmokeEmitters(grid_, desc_.emitters, h, smokeDensity_, temperature_);
    applyBuoyancy(tasks, grid_, smokeDensity_, temperature_, desc_.smoke, input.gravity, h);
    applyVorticityConfinement(tasks, grid_, desc_.smoke.vorticityConfinement, h, vorticity_);
    dissipate(smokeDensity_, desc_.smoke.densityDissipation, h);
    dissipate(temperature_, desc_.smoke.temperatureDissipation, h);
    stats->phase(Phase::Forces).ms += deadline.elapsedMs() - t0;

    t0 = deadline.elapsedMs();
    PressureSolveStats ps;
    const Deadline share = deadline.share(1.0 / (substeps - sub));
    if (Status st = projectVelocity(tasks, grid_, fractions_, h, desc_.density, share, pressureSettings, pressure_, &ps);
        st != Status::Ok)
      log(LogLevel::Error, "fluid '%s': pressure projection failed: %s", desc_.name.c_str(), lastError());
    pressurePhase.iterations += ps.iterations;
    pressurePhase.residual = std::max(pressurePhase.residual, ps.relativeResidual);
    pressurePhase.budgetCut = pressurePhase.budgetCut || ps.budgetCut;
    if (desc_.twoWayCoupling)
      for (size_t c = 0; c < input.colliders.size(); ++c) {
        const FluidCollider& fc = input.colliders[c];
        if (!fc.dynamic || fc.geometry == nullptr) continue;
        const PressureLoad l = pressureLoadOnCollider(grid_, pressure_.poisson, pressure_.pressure.data(),
                                                      *fc.geometry, fc.geometry->shape.translation);
        loadSum[c].force += l.force / substeps;
        loadSum[c].torque += l.torque / substeps;
      }
    pressurePhase.ms += deadline.elapsedMs() - t0;
  }

  bool finite = true;
  for (int a = 0; a < 3 && finite; ++a)
    for (double u : grid_.velocity[a])
      if (!std::isfinite(u)) { finite = false; break; }
  if (!finite) {
    // Nothing bounds a blown-up state from coming back: restart the flow from rest rather
    // than hand NaNs to the host and the rigid bodies.
    for (int a = 0; a < 3; ++a) std::fill(grid_.velocity[a].begin(), grid_.velocity[a].end(), 0.0);
    std::fill(pressure_.pressure.begin(), pressure_.pressure.end(), 0.0);
    stats->diverged = true;
    return;
  }
  if (loads != nullptr)
    for (size_t c = 0; c < input.colliders.size(); ++c)
      if (input.colliders[c].dynamic && desc_.twoWayCoupling)
        loads->push_back(FluidColliderLoad{input.colliders[c].index1, input.colliders[c].generation, loadSum[c]});
}

}  // namespace vp

// Fluid actor step (see fluid_actor.h).
#include "fluid/fluid_actor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/log.h"
#include "core/parallel_for.h"
#include "fluid/cut_cell_components.h"
#include "fluid/fluid_sources.h"
#include "fluid/level_set_solid_extension.h"
#include "fluid/liquid_volume.h"

namespace vp {

// m/s; far above anything a game scene's fluid reaches, far below what a blown-up one does.
constexpr double kMaxFluidSpeed = 1e3;

// The projection sets the flux A_f u_f of a face, and its velocity counts with weight A_f in
// the kinetic energy it minimizes, so on a sliver (a face nearly closed by a solid) the
// velocity is barely constrained: where a static ball crossed the water line, faces 1.4% open
// gained g dt a step that their ghost-fluid pressure difference did not take back (-6.2 m/s
// after 2 s), and advection, which samples a face at full weight, carried that into the flow.
// The liquid around such a face is tied to its well-open neighbours, so after each projection
// slivers take their velocity from them (a flux error of at most a quarter of the difference,
// which the volume correction absorbs). Measured in that tank: at 10%, faces 22% open at the
// water line still fell in bursts (8.8 m/s at 12.9 s); at 25% no liquid cell passed 2.7 m/s
// in 15 s.
constexpr double kMinExtrapolationSourceOpenFraction = 0.25;

Status FluidActor::create(FluidDesc desc, TaskSystem& tasks, std::unique_ptr<FluidActor>* out) {
  VP_TRY(validateFluidDesc(desc));
  std::unique_ptr<FluidActor> actor(new FluidActor(std::move(desc)));
  FluidActor& a = *actor;
  a.tasks_ = &tasks;
  VP_TRY(initMacGrid(a.desc_.grid, a.desc_.sides, &a.grid_));
  VP_TRY(initFaceFractionField(a.desc_.grid, &a.fractions_));
  const size_t cells = static_cast<size_t>(a.grid_.cellCount());
  if (a.desc_.kind == FluidKind::Smoke) {
    a.smokeDensity_.assign(cells, 0.0);
    a.temperature_.assign(cells, a.desc_.smoke.ambientTemperature);
  } else {
    initialLiquidLevelSet(a.grid_, a.desc_.initialLiquid, a.phi_);
    RedistanceStats rs;
    VP_TRY(redistanceLevelSet(tasks, a.grid_.spec, a.phi_.data(), RedistanceSettings{}, a.redistance_, &rs));
    // Colliders are not known yet: the first step's fractions set the cell weights, and the
    // target is re-measured then (liquid created inside a solid does not count).
    a.targetVolume_ = -1.0;
  }
  *out = std::move(actor);
  return Status::Ok;
}

double FluidActor::totalSmoke() const {
  double sum = 0.0;
  for (double d : smokeDensity_) sum += d;
  return sum * grid_.spec.h * grid_.spec.h * grid_.spec.h;
}

double FluidActor::liquidVolume() const {
  if (desc_.kind != FluidKind::Liquid) return 0.0;
  return vp::liquidVolume(*tasks_, grid_.spec, phi_.data(), cellWeights_.empty() ? nullptr : cellWeights_.data());
}

const FluidSurface& FluidActor::surface() {
  if (surfaceStep_ == stepCount_) return surface_;
  surface_ = FluidSurface{};
  surfaceStep_ = stepCount_;
  if (desc_.kind != FluidKind::Liquid) return surface_;
  SurfaceMesh mesh;
  std::vector<Eigen::Vector3d> normals;
  if (Status s = extractLiquidSurface(*tasks_, grid_.spec, phi_.data(), &mesh, &normals, marchingCubes_); !ok(s)) {
    log(LogLevel::Error, "fluid '%s': surface extraction failed: %s", desc_.name.c_str(), lastError());
    return surface_;
  }
  surface_.positions = std::move(mesh.vertices);
  surface_.normals = std::move(normals);
  surface_.triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) surface_.triangles.emplace_back(t[0], t[1], t[2]);
  return surface_;
}

void FluidActor::keepLevelSetHealthy(TaskSystem& tasks) {
  extendLevelSetIntoSolids(grid_.spec, cellWeights_, phi_, solidCells_);
  RedistanceStats rs;
  if (Status s = redistanceLevelSet(tasks, grid_.spec, phi_.data(), RedistanceSettings{}, redistance_, &rs); !ok(s))
    log(LogLevel::Error, "fluid '%s': redistancing failed: %s", desc_.name.c_str(), lastError());
  // Advection and redistancing both lose or gain a little volume every step; a uniform
  // shift of the level set puts it back (the correction moves at most a cell per call, so
  // large mismatches are caught up over a few steps instead of jumping the surface).
  VolumeCorrectionResult vc;
  if (Status s = correctLiquidVolume(tasks, grid_.spec, phi_.data(), cellWeights_.data(), targetVolume_,
                                     VolumeCorrectionSettings{}, &vc);
      !ok(s))
    log(LogLevel::Error, "fluid '%s': volume correction failed: %s", desc_.name.c_str(), lastError());
}

void FluidActor::extrapolateLiquidVelocity(TaskSystem& tasks) {
  VelocityExtrapolationSettings settings;
  // Advection traces at most cflNumber cells (plus the interpolation stencil) from any
  // liquid face within a sub-step.
  settings.layers = static_cast<int>(std::ceil(desc_.solver.cflNumber)) + 2;
  settings.minSourceOpenFraction = kMinExtrapolationSourceOpenFraction;
  if (Status s = extrapolateVelocity(tasks, grid_, fractions_, phi_.data(), settings, extrapolation_); !ok(s)) {
    log(LogLevel::Error, "fluid '%s': velocity extrapolation failed: %s", desc_.name.c_str(), lastError());
    return;
  }
  // Air faces out of reach of the liquid are never projected; left alone they would gather
  // gravity step after step and inflate the CFL sub-step count.
  for (int a = 0; a < 3; ++a) {
    const std::vector<uint8_t>& mark = extrapolation_.mark[a];
    std::vector<double>& u = grid_.velocity[a];
    for (size_t f = 0; f < u.size(); ++f)
      if (mark[f] == kExtrapolationUnreached) u[f] = 0.0;
  }
}

void FluidActor::diffuseVelocity(TaskSystem& tasks, double dt, const Deadline& deadline, ActorStats* stats) {
  const double t0 = deadline.elapsedMs();
  ViscosityStats vs;
  if (Status s = applyViscosity(tasks, grid_, fractions_, liquidPhi(), desc_.kinematicViscosity, dt, deadline,
                                ViscositySettings{}, viscosity_, &vs);
      !ok(s))
    log(LogLevel::Error, "fluid '%s': viscosity failed: %s", desc_.name.c_str(), lastError());
  PhaseStats& phase = stats->phase(Phase::Viscosity);
  phase.iterations += vs.solve.iterations;
  phase.residual = std::max(phase.residual, vs.solve.relativeResidual);
  phase.budgetCut = phase.budgetCut || vs.solve.budgetCut;
  phase.ms += deadline.elapsedMs() - t0;
}

void FluidActor::advectAndSource(TaskSystem& tasks, double h, double maxDisplacement, ActorStats* stats,
                                 const Deadline& deadline) {
  const FluidSolverSettings& solver = desc_.solver;
  const double cell = grid_.spec.h;
  double t0 = deadline.elapsedMs();
  // A liquid's air faces beyond the extrapolated layers are zeroed after the projection and
  // out of reach of the liquid while a sub-step moves things at most cflNumber cells (the
  // layers' premise); when maxSubsteps caps the sub-steps, everything is advected.
  FaceSkipMask skip;
  if (desc_.kind == FluidKind::Liquid && !extrapolation_.mark[0].empty() &&
      maxDisplacement <= solver.cflNumber * cell)
    skip = FaceSkipMask{extrapolation_.mark, kExtrapolationUnreached};
  advectVelocity(tasks, grid_, h, solver.advection, advection_, skip);
  if (desc_.kind == FluidKind::Smoke) {
    // Smoke and heat move through open faces only: a plain trilinear stencil reaches across a
    // plate one cell thick. Cells inside solids hold no smoke and the ambient temperature.
    if (fractionsChanged_) {
      buildCellOpenFaces(tasks, grid_, fractions_, &openFaces_);
      fractionsChanged_ = false;
    }
    std::vector<double>* scalars[2] = {&smokeDensity_, &temperature_};
    const double solidValues[2] = {0.0, desc_.smoke.ambientTemperature};
    advectCellScalars(tasks, grid_, h, solver.advection, scalars, 2, advection_, &openFaces_, solidValues);
  } else {
    // The level set is extended into solids on purpose (level_set_solid_extension.h) and
    // sampled as it is. Cells farther from the surface than the sub-step moves it, plus the
    // forward and backward traces' stencils, keep their sign, and redistancing rewrites them.
    std::vector<double>* scalars[1] = {&phi_};
    advectCellScalars(tasks, grid_, h, solver.advection, scalars, 1, advection_, nullptr, nullptr,
                      maxDisplacement + 3.0 * cell);
  }
  stats->phase(Phase::Advect).ms += deadline.elapsedMs() - t0;

  t0 = deadline.elapsedMs();
  if (desc_.kind == FluidKind::Smoke) {
    applySmokeEmitters(grid_, desc_.emitters, h, smokeDensity_, temperature_);
  } else if (!desc_.emitters.empty() || !desc_.drains.empty()) {
    // Sources change the volume on purpose: the target follows them.
    const double before = vp::liquidVolume(tasks, grid_.spec, phi_.data(), cellWeights_.data());
    applyLiquidEmitters(grid_, desc_.emitters, phi_);
    applyDrains(grid_, desc_.drains, phi_);
    targetVolume_ += vp::liquidVolume(tasks, grid_.spec, phi_.data(), cellWeights_.data()) - before;
  }
  stats->phase(Phase::Forces).ms += deadline.elapsedMs() - t0;

  if (desc_.kind == FluidKind::Liquid) {
    t0 = deadline.elapsedMs();
    keepLevelSetHealthy(tasks);
    stats->phase(Phase::Surface).ms += deadline.elapsedMs() - t0;
  }
}

void FluidActor::applyForces(TaskSystem& tasks, const Vec3& gravity, double h, ActorStats* stats,
                             const Deadline& deadline) {
  const double t0 = deadline.elapsedMs();
  if (desc_.kind == FluidKind::Smoke) {
    applyBuoyancy(tasks, grid_, smokeDensity_, temperature_, desc_.smoke, gravity, h);
    applyVorticityConfinement(tasks, grid_, desc_.smoke.vorticityConfinement, h, vorticity_);
    dissipate(smokeDensity_, desc_.smoke.densityDissipation, h);
    dissipate(temperature_, desc_.smoke.temperatureDissipation, h);
  } else {
    for (int a = 0; a < 3; ++a) {
      if (gravity[a] == 0.0) continue;
      for (double& u : grid_.velocity[a]) u += h * gravity[a];
    }
  }
  stats->phase(Phase::Forces).ms += deadline.elapsedMs() - t0;
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
  const Aabb domain = domainBounds();
  bool sameSet = fractionsValid_ && now.size() == snapshots_.size();
  for (size_t i = 0; sameSet && i < now.size(); ++i)
    sameSet = now[i].index1 == snapshots_[i].index1 && now[i].generation == snapshots_[i].generation;
  // Every recomputed region also gets its split cut cells' minor pieces closed
  // (cut_cell_components.h): without it a plate one cell thick leaks.
  if (!sameSet) {
    // A collider came or went: a full recompute is simpler than tracking the union of
    // everything that changed, and it happens only on such events.
    VP_TRY(computeFaceFractions(geometry.data(), count, &fractions_));
    for (const PreparedCollider* c : geometry)
      VP_TRY(closeSplitCellPieces(*tasks_, geometry.data(), count, c->bounds, &fractions_, nullptr));
    fractionsChanged_ = pressureOperatorStale_ = true;
  } else {
    for (size_t i = 0; i < now.size(); ++i) {
      const ColliderSnapshot& a = snapshots_[i];
      const ColliderSnapshot& b = now[i];
      const bool moved = a.translation != b.translation || a.rotation.coeffs() != b.rotation.coeffs() ||
                         a.linearVelocity != b.linearVelocity || a.angularVelocity != b.angularVelocity;
      // A body moving elsewhere in the world changes no face here (and must not make the
      // pressure operator look stale).
      if (!moved || !(a.bounds.overlaps(domain) || b.bounds.overlaps(domain))) continue;
      VP_TRY(updateFaceFractions(geometry.data(), count, a.bounds, b.bounds, &fractions_));
      // A collider moving a little per step (a paddle) has nearly the same box before and
      // after: one pass over their union instead of two over the overlap.
      if (a.bounds.overlaps(b.bounds)) {
        Aabb both;
        both.lo = a.bounds.lo.cwiseMin(b.bounds.lo);
        both.hi = a.bounds.hi.cwiseMax(b.bounds.hi);
        VP_TRY(closeSplitCellPieces(*tasks_, geometry.data(), count, both, &fractions_, nullptr));
      } else {
        VP_TRY(closeSplitCellPieces(*tasks_, geometry.data(), count, a.bounds, &fractions_, nullptr));
        VP_TRY(closeSplitCellPieces(*tasks_, geometry.data(), count, b.bounds, &fractions_, nullptr));
      }
      fractionsChanged_ = pressureOperatorStale_ = true;
    }
  }
  snapshots_ = std::move(now);
  fractionsValid_ = true;
  return Status::Ok;
}

Aabb FluidActor::domainBounds() const {
  const MacGridSpec& s = grid_.spec;
  return Aabb{s.origin, s.origin + s.h * Eigen::Vector3d(s.nx, s.ny, s.nz)};
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
      for (int64_t f = b; f < e; ++f) {
        // NaN compares false both ways; count it as infinitely fast so the guard sees it.
        const double faceSpeed = std::abs(u[static_cast<size_t>(f)]);
        if (!(faceSpeed <= r.v)) r.v = std::isnan(faceSpeed) ? std::numeric_limits<double>::infinity() : faceSpeed;
      }
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
  if (desc_.kind == FluidKind::Liquid) {
    cellOpenFractions(tasks, fractions_, &cellWeights_);
    if (targetVolume_ < 0.0) {
      targetVolume_ = vp::liquidVolume(tasks, grid_.spec, phi_.data(), cellWeights_.data());
      extrapolateLiquidVelocity(tasks);
    }
  }
  stats->phase(Phase::Fractions).ms += deadline.elapsedMs() - t0;

  // Nothing outside step() writes the velocities, so the speed the last step ended with is
  // the speed this one starts with.
  if (speedAtEnd_ < 0.0) speedAtEnd_ = maxSpeed(tasks);
  double speed = speedAtEnd_;
  for (const FluidCollider& c : input.colliders)
    if (c.geometry != nullptr && c.geometry->bounds.overlaps(domainBounds()))
      speed = std::max(speed, c.geometry->shape.linearVelocity.norm() +
                                  c.geometry->shape.angularVelocity.norm() * c.geometry->boundRadius);
  const int substeps = std::clamp(static_cast<int>(std::ceil(speed * dt / (solver.cflNumber * s.h))), 1,
                                  solver.maxSubsteps);
  const double h = dt / substeps;

  std::vector<PressureLoad> loadSum(input.colliders.size());
  PressureSolveSettings pressureSettings;
  pressureSettings.tolerance = solver.pressureTolerance;
  pressureSettings.maxIterations = solver.pressureMaxIterations;
  // A projection the budget skips leaves the divergence it should remove in the flow; it
  // grows step after step, speeds rise, the CFL sub-steps multiply and the next frames cost
  // more, so the budget cuts deeper (measured: the default scene's liquid then ran 4 sub-steps
  // a frame and 25% of the frames overran 16 ms). Two multigrid-preconditioned iterations cut
  // the residual about a hundredfold, so they run even past the deadline.
  pressureSettings.minIterations = std::min(4, solver.pressureMaxIterations);
  // A liquid's operator follows its surface every sub-step; smoke's changes only with the
  // fractions.
  PhaseStats& pressurePhase = stats->phase(Phase::Pressure);
  for (int sub = 0; sub < substeps; ++sub) {
    advectAndSource(tasks, h, speed * h, stats, deadline);
    if (desc_.kinematicViscosity > 0.0) diffuseVelocity(tasks, h, deadline.share(1.0 / (3 * (substeps - sub))), stats);
    applyForces(tasks, input.gravity, h, stats, deadline);

    t0 = deadline.elapsedMs();
    PressureSolveStats ps;
    const Deadline share = deadline.share(1.0 / (substeps - sub));
    pressureSettings.operatorUnchanged = desc_.kind == FluidKind::Smoke && !pressureOperatorStale_;
    pressureOperatorStale_ = false;
    if (Status st = projectVelocity(tasks, grid_, fractions_, h, desc_.density, share, pressureSettings, pressure_, &ps,
                                    liquidPhi());
        st != Status::Ok)
      log(LogLevel::Error, "fluid '%s': pressure projection failed: %s", desc_.name.c_str(), lastError());
    pressurePhase.iterations += ps.iterations;
    pressurePhase.residual = std::max(pressurePhase.residual, ps.relativeResidual);
    pressurePhase.budgetCut = pressurePhase.budgetCut || ps.budgetCut;
    if (desc_.twoWayCoupling)
      for (size_t c = 0; c < input.colliders.size(); ++c) {
        const FluidCollider& fc = input.colliders[c];
        if (!fc.dynamic || fc.geometry == nullptr) continue;
        const PressureLoad l = pressureLoadOnCollider(grid_, fractions_, pressure_.poisson, pressure_.pressure.data(), desc_.density,
                                                      *fc.geometry, fc.geometry->shape.translation);
        loadSum[c].force += l.force / substeps;
        loadSum[c].torque += l.torque / substeps;
        loadSum[c].addedMass += l.addedMass / substeps;
      }
    pressurePhase.ms += deadline.elapsedMs() - t0;
    if (desc_.kind == FluidKind::Liquid) {
      t0 = deadline.elapsedMs();
      extrapolateLiquidVelocity(tasks);
      stats->phase(Phase::Surface).ms += deadline.elapsedMs() - t0;
    }
  }

  // Non-finite or absurd speeds (the deformables' guard uses the same kind of bound) mean the
  // step blew up; nothing brings such a flow back.
  speedAtEnd_ = maxSpeed(tasks);
  const bool finite = std::isfinite(speedAtEnd_) && speedAtEnd_ <= kMaxFluidSpeed;
  if (!finite) {
    // Restart the flow from rest rather than hand NaNs or absurd loads to the host and the
    // rigid bodies.
    for (int a = 0; a < 3; ++a) std::fill(grid_.velocity[a].begin(), grid_.velocity[a].end(), 0.0);
    std::fill(pressure_.pressure.begin(), pressure_.pressure.end(), 0.0);
    speedAtEnd_ = 0.0;
    stats->diverged = true;
    return;
  }
  // The load is the mean over this step and acts during the next one (a delay of one step:
  // explicit coupling). Extrapolating it one step ahead to cancel the delay was tried and made
  // a floating box unstable (the pressure also carries the added-mass reaction, which an
  // extrapolation amplifies); the plain delay lets bobbing decay, slowly, in an inviscid tank.
  if (loads != nullptr)
    for (size_t c = 0; c < input.colliders.size(); ++c)
      if (input.colliders[c].dynamic && desc_.twoWayCoupling)
        loads->push_back(FluidColliderLoad{input.colliders[c].index1, input.colliders[c].generation, loadSum[c]});
}

}  // namespace vp

// Fluid actor step (see fluid_actor.h).
#include "fluid/fluid_actor.h"
#include "fluid/solids/surface_pressure_load.h"
#include "fluid/solids/viscous_traction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/log.h"
#include "core/parallel_for.h"
#include "fluid/fluid_sources.h"
#include "fluid/grid_index.h"
#include "fluid/solids/cut_cell_components.h"
#include "fluid/solids/sliver_cells.h"
#include "fluid/surface/level_set_solid_extension.h"
#include "fluid/surface/liquid_volume.h"

namespace vp {

// m/s; far above anything a game scene's fluid reaches, far below what a blown-up one does.
constexpr double kMaxFluidSpeed = 1e3;

// The projection sets the flux A_f u_f of a face, and its velocity counts with weight A_f in
// the kinetic energy it minimizes, so on a sliver (a face nearly closed by a solid) the
// velocity is barely constrained: where a static ball crossed the water line, such faces
// gained g dt a step that their ghost-fluid pressure difference did not take back, and
// advection, which samples a face at full weight, carried that into the flow. The liquid
// around such a face is tied to its well-open neighbours, so after each projection faces less
// open than this take their velocity from them (a flux error of at most this fraction of the
// difference, which the volume correction absorbs). A lower bound left faces at the water line
// falling in bursts (docs/choices.md, Fluids: the stirred tank).
constexpr double kMinExtrapolationSourceOpenFraction = 0.25;

namespace {

// Whether some solid of the step's input is `which`: the coupling's stages run only then.
template <class Which>
bool anySolid(const FluidStepInput& input, const Which& which) {
  return std::any_of(input.colliders.begin(), input.colliders.end(), which);
}

// Adds a sub-step's per-vertex values to their mean over the step (sized at the first).
void addMeanOverSubsteps(const Array<Vec3>& values, int substeps, Array<Vec3>* mean) {
  if (mean->empty()) mean->assign(values.size(), Vec3::Zero());
  for (size_t v = 0; v < mean->size(); ++v) (*mean)[v] += values[v] / substeps;
}

// A sub-step's share of a rigid body's drag over the step.
RigidDrag meanShare(const RigidDrag& d, int substeps) {
  return RigidDrag{d.linear / substeps, d.angular / substeps, d.forceAtRest / substeps, d.torqueAtRest / substeps};
}

}  // namespace

Status FluidActor::create(FluidDesc desc, TaskSystem& tasks, std::unique_ptr<FluidActor>* out) {
  VP_TRY(validateFluidDesc(desc));
  std::unique_ptr<FluidActor> actor(new FluidActor(std::move(desc)));
  FluidActor& a = *actor;
  a.tasks_ = &tasks;
  a.slabs_.assign(static_cast<size_t>(FluidSlice::Count), SliceSizer(a.desc_.solver.samplesPerSlice));
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
  a.publish();
  a.stepCount_ = 0;
  *out = std::move(actor);
  return Status::Ok;
}

double FluidActor::totalSmoke() const {
  double sum = 0.0;
  for (double d : shown_.smokeDensity) sum += d;
  return sum * grid_.spec.h * grid_.spec.h * grid_.spec.h;
}

double FluidActor::liquidVolume() const {
  if (desc_.kind != FluidKind::Liquid) return 0.0;
  const Array<double>& weights = shown_.cellWeights;
  return vp::liquidVolume(*tasks_, grid_.spec, shown_.levelSet.data(), weights.empty() ? nullptr : weights.data());
}

Status FluidActor::surface(const FluidSurface** out) {
  *out = &surface_;
  if (surfaceStep_ == stepCount_) return Status::Ok;
  surface_ = FluidSurface{};
  if (desc_.kind != FluidKind::Liquid) {
    surfaceStep_ = stepCount_;
    return Status::Ok;
  }
  SurfaceMesh mesh;
  Array<Eigen::Vector3d> normals;
  Status s = extractLiquidSurface(*tasks_, grid_.spec, shown_.levelSet.data(), &mesh, &normals, marchingCubes_);
  if (ok(s) && injectedFailure_ == Phase::Surface) {
    injectedFailure_.reset();
    s = fail(Status::Internal, "failure injected by a test");
  }
  if (!ok(s)) return addErrorContext(s, "fluid '" + desc_.name + "': surface extraction");
  surface_.positions.assign(mesh.vertices.begin(), mesh.vertices.end());
  surface_.normals = std::move(normals);
  surface_.triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) surface_.triangles.emplace_back(t[0], t[1], t[2]);
  surfaceStep_ = stepCount_;
  return Status::Ok;
}

bool FluidActor::phaseOk(Phase phase, const char* what, Status status) {
  if (ok(status) && injectedFailure_ == phase) {
    injectedFailure_.reset();
    status = fail(Status::Internal, "failure injected by a test");
  }
  if (ok(status)) return true;
  log(LogLevel::Error, "fluid '%s': %s failed: %s", desc_.name.c_str(), what, lastError());
  if (step_ && step_->stats) step_->stats->phase(phase).failed = true;
  return false;
}

bool FluidActor::keepLevelSetHealthySlice() {
  StepInProgress& st = *step_;
  LevelSetUpkeep& u = st.levelSet;
  TaskSystem& tasks = *st.input.tasks;
  const int64_t slice = slabSamples(FluidSlice::LevelSet);
  auto failed = [&](const char* what, Status s) { return !phaseOk(Phase::Surface, what, s); };
  bool done = false;  // the run in progress; its samples are the slice's work
  switch (u.stage) {
    case LevelSetUpkeep::Extend:
      if (failed("solid extension", u.extension.prepare(grid_.spec, cellWeights_, phi_, solidCells_, slice))) break;
      u.stage = LevelSetUpkeep::Extending;
      [[fallthrough]];
    case LevelSetUpkeep::Extending:
      done = u.extension.advance();
      sliceWork_ = u.extension.lastSliceSamples();
      if (!done) return false;
      u.stage = LevelSetUpkeep::Redistancing;
      if (failed("redistancing",
                 u.redistance.prepare(tasks, grid_.spec, phi_.data(), RedistanceSettings{}, redistance_, slice,
                                      cellWeights_.size() == phi_.size() ? cellWeights_.data() : nullptr)))
        u.redistance = RedistanceRun{};
      return false;
    case LevelSetUpkeep::Redistancing:
      done = u.redistance.advance();
      sliceWork_ = u.redistance.lastSliceSamples();
      if (!done) return false;
      u.stage = LevelSetUpkeep::Correcting;
      // Advection and redistancing both lose or gain a little volume every step; a uniform
      // shift of the level set puts it back (the correction moves at most a cell per call, so
      // large mismatches are caught up over a few steps instead of jumping the surface).
      if (failed("volume correction", u.volume.prepare(tasks, grid_.spec, phi_.data(), cellWeights_.data(),
                                                       targetVolume_, VolumeCorrectionSettings{}, slice)))
        u.volume = VolumeCorrectionRun{};
      return false;
    case LevelSetUpkeep::Correcting:
      done = u.volume.advance();
      sliceWork_ = u.volume.lastSliceSamples();
      if (!done) return false;
      break;
  }
  u.stage = LevelSetUpkeep::Extend;
  return true;
}

VelocityExtrapolationSettings FluidActor::extrapolationSettings() const {
  VelocityExtrapolationSettings settings;
  // Advection traces at most cflNumber cells (plus the interpolation stencil) from any
  // liquid face within a sub-step.
  settings.layers = static_cast<int>(std::ceil(desc_.solver.cflNumber)) + 2;
  settings.minSourceOpenFraction = kMinExtrapolationSourceOpenFraction;
  // Air faces out of reach of the liquid are never projected; left alone they would gather
  // gravity step after step and inflate the CFL sub-step count.
  settings.zeroUnreached = true;
  return settings;
}

void FluidActor::extrapolateLiquidVelocity() {
  phaseOk(Phase::Advect, "velocity extrapolation",
          extrapolateVelocity(*tasks_, grid_, fractions_, phi_.data(), extrapolationSettings(), extrapolation_));
}

bool FluidActor::extrapolateLiquidVelocitySlice() {
  StepInProgress& st = *step_;
  if (!st.extrapolating) {
    if (!phaseOk(Phase::Advect, "velocity extrapolation",
                 st.extrapolation.prepare(*st.input.tasks, grid_, fractions_, phi_.data(), extrapolationSettings(),
                                          extrapolation_, slabSamples(FluidSlice::Extrapolate))))
      return true;
    st.extrapolating = true;
  }
  const bool done = st.extrapolation.advance();
  sliceWork_ = st.extrapolation.lastSliceSamples();
  if (!done) return false;
  st.extrapolating = false;
  return true;
}

void FluidActor::diffuseVelocity() {
  ViscosityStats vs;
  ViscositySettings settings;
  // A dynamic body takes its viscous traction from the solve (addSubstepLoads).
  settings.recordSolidExchange =
      desc_.twoWayCoupling &&
      anySolid(step_->input, [](const FluidCollider& c) { return c.dynamic && c.geometry != nullptr; });
  phaseOk(Phase::Viscosity, "viscosity",
          applyViscosity(*step_->input.tasks, grid_, fractions_, liquidPhi(), desc_.kinematicViscosity, step_->h,
                         Deadline{}, settings, viscosity_, &vs));
  PhaseStats& phase = step_->stats->phase(Phase::Viscosity);
  phase.iterations += vs.solve.iterations;
  phase.residual = std::max(phase.residual, vs.solve.relativeResidual);
}

bool FluidActor::advectVelocitySlab() {
  StepInProgress& st = *step_;
  if (!st.advecting) {
    const FluidSolverSettings& solver = desc_.solver;
    // A liquid's air faces beyond the extrapolated layers are zeroed after the projection and
    // out of reach of the liquid while a sub-step moves things at most cflNumber cells (the
    // layers' premise); when maxSubsteps caps the sub-steps, everything is advected.
    FaceSkipMask skip;
    if (desc_.kind == FluidKind::Liquid && !extrapolation_.mark[0].empty() &&
        st.speed * st.h <= solver.cflNumber * grid_.spec.h)
      skip = FaceSkipMask{extrapolation_.mark, kExtrapolationUnreached};
    st.velocityAdvection.prepare(*st.input.tasks, grid_, st.h, solver.advection, advection_, skip);
    st.advecting = true;
  }
  const bool done = withSliceStop(
      [&](const Deadline* stop) { return st.velocityAdvection.runSlice(slabSamples(FluidSlice::AdvectVelocity), stop); });
  sliceWork_ = st.velocityAdvection.lastSliceSamples();
  if (!done) return false;
  st.velocityAdvection.finish();
  st.advecting = false;
  return true;
}

bool FluidActor::advectScalarsSlab() {
  StepInProgress& st = *step_;
  if (!st.advecting) {
    TaskSystem& tasks = *st.input.tasks;
    if (desc_.kind == FluidKind::Smoke) {
      const AdvectionScheme scheme = desc_.solver.advection;
      // Smoke and heat move through open faces only: a plain trilinear stencil reaches across
      // a plate one cell thick. Cells inside solids hold no smoke and the ambient temperature.
      if (fractionsChanged_) {
        buildCellOpenFaces(tasks, grid_, fractions_, &openFaces_);
        fractionsChanged_ = false;
      }
      Array<double>* scalars[2] = {&smokeDensity_, &temperature_};
      const double solidValues[2] = {0.0, desc_.smoke.ambientTemperature};
      st.scalarAdvection.prepare(tasks, grid_, st.h, scheme, scalars, 2, advection_, &openFaces_, solidValues, 0.0,
                                 /*conservedField=*/0);
    } else {
      // The level set is extended into solids on purpose (level_set_solid_extension.h) and
      // sampled as it is. Cells farther from the surface than the sub-step moves it, plus the
      // forward and backward traces' stencils, keep their sign, and redistancing rewrites them.
      // Beyond the open sides is air. Semi-Lagrangian whatever the desc's scheme
      // (kLevelSetAdvection).
      Array<double>* scalars[1] = {&phi_};
      st.scalarAdvection.prepare(tasks, grid_, st.h, kLevelSetAdvection, scalars, 1, advection_, nullptr, nullptr,
                                 st.speed * st.h + 3.0 * grid_.spec.h, /*conservedField=*/-1,
                                 /*levelSetField=*/0);
    }
    st.advecting = true;
  }
  const bool done = withSliceStop(
      [&](const Deadline* stop) { return st.scalarAdvection.runSlice(slabSamples(FluidSlice::AdvectScalars), stop); });
  sliceWork_ = st.scalarAdvection.lastSliceSamples();
  if (!done) return false;
  st.advecting = false;
  return true;
}

void FluidActor::applySources() {
  const double h = step_->h;
  if (desc_.kind == FluidKind::Smoke) {
    applySmokeEmitters(grid_, desc_.emitters, h, smokeDensity_, temperature_);
  } else if (!desc_.emitters.empty() || !desc_.drains.empty()) {
    // Sources change the volume on purpose: the target follows them.
    TaskSystem& tasks = *step_->input.tasks;
    const double before = vp::liquidVolume(tasks, grid_.spec, phi_.data(), cellWeights_.data());
    applyLiquidEmitters(grid_, desc_.emitters, phi_);
    applyDrains(grid_, desc_.drains, phi_);
    targetVolume_ += vp::liquidVolume(tasks, grid_.spec, phi_.data(), cellWeights_.data()) - before;
  }
}

void FluidActor::planForces() {
  StepInProgress& st = *step_;
  st.forces.reset(*st.input.tasks);
  if (desc_.kind == FluidKind::Smoke)
    addSmokeForcePasses(st.forces, grid_, smokeDensity_, temperature_, desc_.smoke, st.input.gravity, st.h, vorticity_);
  else
    addGravityPasses(st.forces, grid_, st.input.gravity, st.h);
}

bool FluidActor::applyForcesSlice() {
  StepInProgress& st = *step_;
  const bool done =
      withSliceStop([&](const Deadline* stop) { return st.forces.runSlice(slabSamples(FluidSlice::Forces), stop); });
  sliceWork_ = st.forces.lastSliceSamples();
  return done;
}

Status FluidActor::addFractionUpdatePasses(SlabPasses& passes, SlabPasses& surfacePasses) {
  std::vector<const PreparedCollider*>& geometry = step_->fractionColliders;
  std::vector<ColliderSnapshot> now;
  for (const FluidCollider& c : step_->input.colliders) {
    if (c.geometry == nullptr) continue;
    geometry.push_back(c.geometry);
    const ColliderShape& s = c.geometry->shape;
    now.push_back(ColliderSnapshot{c.index1, c.generation, c.geometry->bounds, s.rotation, s.translation,
                                   s.linearVelocity, s.angularVelocity, c.geometry->surfaceMoves});
  }
  const int count = static_cast<int>(geometry.size());
  const Aabb domain = domainBounds();
  bool sameSet = fractionsValid_ && now.size() == snapshots_.size();
  for (size_t i = 0; sameSet && i < now.size(); ++i)
    sameSet = now[i].index1 == snapshots_[i].index1 && now[i].generation == snapshots_[i].generation;
  // Every recomputed region also gets its split cut cells' minor pieces closed
  // (cut_cell_components.h: without it a plate one cell thick leaks), then its sliver cells
  // (sliver_cells.h: they hold absurd pressures).
  auto tidy = [&](SlabPasses& list, const Aabb& box) -> Status {
    VP_TRY(addSplitCellPasses(list, geometry.data(), count, box, &fractions_, nullptr));
    addSliverCellPasses(list, box, &fractions_);
    return Status::Ok;
  };
  if (!sameSet) {
    // A collider came or went: a full recompute is simpler than tracking the union of
    // everything that changed, and it happens only on such events.
    VP_TRY(addFaceFractionPasses(passes, geometry.data(), count, &fractions_));
    for (const PreparedCollider* c : geometry) VP_TRY(tidy(passes, c->bounds));
    fractionsChanged_ = pressureOperatorStale_ = true;
  } else {
    for (size_t i = 0; i < now.size(); ++i) {
      const ColliderSnapshot& a = snapshots_[i];
      const ColliderSnapshot& b = now[i];
      const bool moved = a.translation != b.translation || a.rotation.coeffs() != b.rotation.coeffs() ||
                         a.linearVelocity != b.linearVelocity || a.angularVelocity != b.angularVelocity ||
                         a.surfaceMoves != b.surfaceMoves;
      // A body moving elsewhere in the world changes no face here (and must not make the
      // pressure operator look stale).
      if (!moved || !(a.bounds.overlaps(domain) || b.bounds.overlaps(domain))) continue;
      // Deformables come after the rigid colliders in the input, so their list running after
      // the other keeps the order of the updates.
      SlabPasses& list = (b.generation & kDeformableSolidBit) ? surfacePasses : passes;
      VP_TRY(addFaceFractionUpdatePasses(list, geometry.data(), count, a.bounds, b.bounds, &fractions_));
      for (const Aabb& box : boxesToUpdate(a.bounds, b.bounds)) VP_TRY(tidy(list, box));
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
    const Array<double>& u = grid_.velocity[a];
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
  while (!advance(input, SliceBudget{}, stats)) {  // an unlimited share: one call
  }
  if (loads != nullptr) loads->insert(loads->end(), shown_.loads.begin(), shown_.loads.end());
}

bool FluidActor::advance(const FluidStepInput& input, const SliceBudget& budget, ActorStats* stats) {
  if (job_.done()) beginStep(input);
  step_->stats = stats;
  const Clock& clock = budget.share.clock();
  sliceTargetMs_ = budget.targetSliceMs;
  sliceClock_ = clock;
  int ran = 0;
  int64_t workRun = 0;
  maxSliceMs_ = 0.0;
  while (!job_.done()) {
    // A slice of a kind never measured is expected to cost nothing: it runs while any time is
    // left (an unlimited share has infinite time left).
    const double remaining = budget.share.remainingMs();
    const bool fits = remaining > 0.0 && remaining >= job_.expectedNextMs();
    if (!fits && workRun >= budget.minWork) break;
    const FluidSlice kind = static_cast<FluidSlice>(job_.nextKind());
    sliceWork_ = 0;
    const double ms = job_.runNext(clock);
    const int64_t work = sliceWork_ > 0 ? sliceWork_ : grid_.cellCount();
    work_.add(work);
    workRun += work;
    stats->phase(phaseOf(kind)).ms += ms;
    maxSliceMs_ = std::max(maxSliceMs_, ms);
    if (runsSlabs(kind)) slabs_[static_cast<size_t>(kind)].noteSlice(ms, budget.targetSliceMs);
    ++ran;
  }
  stats->slices += ran;
  stats->completedStep = job_.done();
  stats->progress = progress();
  if (!job_.done()) return false;
  stats->simulatedDt = step_->input.dt;
  stats->substeps = step_->substeps;
  stats->diverged = stats->diverged || step_->diverged;
  for (SliceSizer& sizer : slabs_) sizer.adapt(budget.targetSliceMs);
  lastStepSlices_ = job_.slicesRun();
  work_.finish(step_->substeps);
  step_.reset();
  return true;
}

void FluidActor::abandonStep() {
  job_.reset();
  step_.reset();
  work_.finish(work_.parts());
  restorePublished();
  fractionsValid_ = false;
  fractionsChanged_ = true;
  pressureOperatorStale_ = true;
}

double FluidActor::progress() const {
  if (job_.done()) return step_ ? 1.0 : 0.0;
  return work_.fraction();
}

FluidControls FluidActor::controls() const {
  return pendingControls_ ? *pendingControls_
                          : FluidControls{desc_.smoke, desc_.kinematicViscosity, desc_.emitters, desc_.sides};
}

Status FluidActor::setControls(const FluidControls& controls) {
  if (controls.emitters.size() != desc_.emitters.size())
    return fail(Status::InvalidArgument, "emitters: %zu given, the fluid has %zu (they can be changed, not added)",
                controls.emitters.size(), desc_.emitters.size());
  VP_TRY(validateFluidControls(controls));
  pendingControls_ = controls;
  return Status::Ok;
}

void FluidActor::beginStep(const FluidStepInput& input) {
  if (pendingControls_) {
    desc_.smoke = pendingControls_->smoke;
    desc_.kinematicViscosity = pendingControls_->kinematicViscosity;
    desc_.emitters = pendingControls_->emitters;
    if (pendingControls_->sides != desc_.sides) {
      // The projection closes the faces of a side that became a Wall (and opens those of an
      // Open one); the operator and what is built on the fractions follow the new sides.
      desc_.sides = grid_.sides = pendingControls_->sides;
      invalidateDerived();
    }
    pendingControls_.reset();
  }
  step_ = std::make_unique<StepInProgress>();
  step_->input = input;
  std::vector<SolidMotionHistory::Entry> motions;
  for (const FluidCollider& c : input.colliders) motions.push_back({c.index1, c.generation, c.motion});
  step_->seen = solidMotions_.begin(motions, input.dt);
  job_.reset();
  work_.begin();
  job_.thenOnce(static_cast<int>(FluidSlice::Fractions), [this] { planFractionUpdate(); });
  job_.then(static_cast<int>(FluidSlice::Fractions),
            [this] { return runFractionPassesSlice(step_->fractionUpdate, FluidSlice::Fractions); });
  if (anySolid(input, [](const FluidCollider& c) { return (c.generation & kDeformableSolidBit) != 0; }))
    job_.then(static_cast<int>(FluidSlice::SurfaceFractions),
              [this] { return runFractionPassesSlice(step_->surfaceFractionUpdate, FluidSlice::SurfaceFractions); });
  job_.then(static_cast<int>(FluidSlice::CellWeights),
            [this] { return runFractionPassesSlice(step_->cellWeightUpdate, FluidSlice::CellWeights); });
  job_.thenOnce(static_cast<int>(FluidSlice::Plan), [this] { finishFractionUpdate(); });
  job_.thenOnce(static_cast<int>(FluidSlice::Plan), [this] { planSubsteps(); });
}

void FluidActor::planFractionUpdate() {
  TaskSystem& tasks = *step_->input.tasks;
  SlabPasses& passes = step_->fractionUpdate;
  SlabPasses& surfacePasses = step_->surfaceFractionUpdate;
  passes.reset(tasks);
  surfacePasses.reset(tasks);
  step_->cellWeightUpdate.reset(tasks);
  if (!phaseOk(Phase::Fractions, "face fractions", addFractionUpdatePasses(passes, surfacePasses))) {
    passes.reset(tasks);
    surfacePasses.reset(tasks);
  }
  if (desc_.kind == FluidKind::Liquid) addCellOpenFractionPasses(step_->cellWeightUpdate, fractions_, &cellWeights_);
}

bool FluidActor::runFractionPassesSlice(SlabPasses& passes, FluidSlice kind) {
  const bool done = withSliceStop([&](const Deadline* stop) { return passes.runSlice(slabSamples(kind), stop); });
  // An empty list (no such solid moved) did next to nothing, not a pass over the grid.
  sliceWork_ = std::max<int64_t>(1, passes.lastSliceSamples());
  return done;
}

void FluidActor::finishFractionUpdate() {
  // The first step's start: the liquid's volume to keep, and a velocity field to advect by.
  // The volume is all the liquid the definition asked for, solids or not (no cell weights):
  // a solid standing in it displaces the liquid, whose level rises, instead of deleting the
  // liquid where it stands.
  if (desc_.kind == FluidKind::Liquid && targetVolume_ < 0.0) {
    targetVolume_ = vp::liquidVolume(*step_->input.tasks, grid_.spec, phi_.data(), nullptr);
    extrapolateLiquidVelocity();
  }
}

void FluidActor::planSubsteps() {
  StepInProgress& st = *step_;
  const FluidSolverSettings& solver = desc_.solver;
  // Nothing outside the step writes the working velocities, so the speed the last step
  // ended with is the speed this one starts with.
  if (speedAtEnd_ < 0.0) speedAtEnd_ = maxSpeed(*st.input.tasks);
  st.speed = speedAtEnd_;
  double solidSpeed = 0.0;
  for (const FluidCollider& c : st.input.colliders)
    if (c.geometry != nullptr && c.geometry->bounds.overlaps(domainBounds()))
      solidSpeed = std::max(solidSpeed, solidSpeedBound(*c.geometry));
  st.speed = std::max(st.speed, solidSpeed);
  planEnergyBound(solidSpeed);
  st.substeps = clampIndex(std::ceil(st.speed * st.input.dt / (solver.cflNumber * grid_.spec.h)), 1, solver.maxSubsteps);
  st.h = st.input.dt / st.substeps;
  // The plan paces the step by its expected work (frame_plan.h), which follows its sub-steps.
  work_.expectParts(st.substeps);
  st.loadSum.assign(st.input.colliders.size(), PressureLoad{});
  st.vertexForceSum.assign(st.input.colliders.size(), Array<Vec3>{});
  st.dragSum.assign(st.input.colliders.size(), VertexDrag{});
  st.rigidDragSum.assign(st.input.colliders.size(), RigidDrag{});
  for (int sub = 0; sub < st.substeps; ++sub) queueSubstep(sub);
  job_.thenOnce(static_cast<int>(FluidSlice::Publish), [this] { publish(); });
}

void FluidActor::planEnergyBound(double solidSpeed) {
  StepInProgress& st = *step_;
  TaskSystem& tasks = *st.input.tasks;
  const double dt = st.input.dt;
  // As with the speed: the last step's end is this one's start.
  if (kineticAtEnd_ < 0.0) kineticAtEnd_ = fluidKineticEnergy(tasks, grid_, fractions_, liquidPhi(), desc_.density);
  st.energy.kineticStart = kineticAtEnd_;
  double emitterSpeed = 0.0, emitted = 0.0, emittedHeat = 0.0;
  for (const FluidEmitter& e : desc_.emitters) {
    if (!e.enabled) continue;
    emitterSpeed = std::max(emitterSpeed, e.velocity.norm());
    emitted += std::abs(e.densityRate) * dt;
    emittedHeat = std::max(emittedHeat, std::abs(e.temperature - desc_.smoke.ambientTemperature));
  }
  st.energyBoundarySpeed = std::max(solidSpeed, emitterSpeed);
  const double gravity = st.input.gravity.norm();
  if (desc_.kind == FluidKind::Liquid) {
    st.energyAcceleration = gravity;
    return;
  }
  const double densityMax = largestDeviation(tasks, smokeDensity_, 0.0) + emitted;
  const double heatMax = std::max(largestDeviation(tasks, temperature_, desc_.smoke.ambientTemperature), emittedHeat);
  const double buoyancy = smokeAccelerationBound(desc_.smoke, gravity, densityMax, heatMax, 0.0);
  st.energyAcceleration = smokeAccelerationBound(desc_.smoke, gravity, densityMax, heatMax,
                                                 std::max(st.speed, emitterSpeed) + buoyancy * dt);
}

bool FluidActor::energyBlewUp() {
  StepInProgress& st = *step_;
  const double h = grid_.spec.h;
  const double volume = desc_.kind == FluidKind::Liquid ? std::max(targetVolume_, 0.0)
                                                        : static_cast<double>(grid_.cellCount()) * h * h * h;
  const double mass = desc_.density * volume;
  st.energy.kineticEnd = fluidKineticEnergy(*st.input.tasks, grid_, fractions_, liquidPhi(), desc_.density);
  st.energy.boundedWork = fluidSourceWorkBound(st.energy.kineticStart, mass, st.energyAcceleration,
                                               st.energyBoundarySpeed, st.input.dt);
  if (!StepEnergyGuard::blewUp(st.energy, mass)) return false;
  log(LogLevel::Warning, "fluid step blew up: its kinetic energy rose %g J beyond the %g J its sources and moving "
      "solids can put in (%g -> %g J)", StepEnergyGuard::unexplainedGain(st.energy), st.energy.boundedWork,
      st.energy.kineticStart, st.energy.kineticEnd);
  return true;
}

void FluidActor::queueSubstep(int) {
  auto once = [this](FluidSlice kind, void (FluidActor::*stage)()) {
    job_.thenOnce(static_cast<int>(kind), [this, stage] { (this->*stage)(); });
  };
  const bool liquid = desc_.kind == FluidKind::Liquid;
  job_.then(static_cast<int>(FluidSlice::AdvectVelocity), [this] { return advectVelocitySlab(); });
  job_.then(static_cast<int>(FluidSlice::AdvectScalars), [this] { return advectScalarsSlab(); });
  once(FluidSlice::Sources, &FluidActor::applySources);
  if (liquid) job_.then(static_cast<int>(FluidSlice::LevelSet), [this] { return keepLevelSetHealthySlice(); });
  if (desc_.kinematicViscosity > 0.0) once(FluidSlice::Viscosity, &FluidActor::diffuseVelocity);
  once(FluidSlice::Forces, &FluidActor::planForces);
  job_.then(static_cast<int>(FluidSlice::Forces), [this] { return applyForcesSlice(); });
  job_.then(static_cast<int>(FluidSlice::PressureSetup), [this] { return setUpProjectionSlice(); });
  job_.then(static_cast<int>(FluidSlice::PressureIteration), [this] { return iterateProjection(); });
  job_.then(static_cast<int>(FluidSlice::PressureUpdate), [this] { return finishProjectionSlice(); });
  if (desc_.twoWayCoupling && anySolid(step_->input, [](const FluidCollider& c) { return c.dynamic; }))
    once(FluidSlice::Loads, &FluidActor::addSubstepLoads);
  if (liquid)
    job_.then(static_cast<int>(FluidSlice::Extrapolate), [this] { return extrapolateLiquidVelocitySlice(); });
}

bool FluidActor::setUpProjectionSlice() {
  StepInProgress& st = *step_;
  if (st.projectionPrepared) {
    if (st.projectionFailed) return true;
    const bool done = withSliceStop([&](const Deadline* stop) { return st.projection.advanceSetup(stop); });
    sliceWork_ = st.projection.lastSliceSamples();
    return done;
  }
  PressureSolveSettings settings;
  settings.tolerance = desc_.solver.pressureTolerance;
  settings.maxIterations = desc_.solver.pressureMaxIterations;
  // A liquid's operator follows its surface every sub-step; smoke's changes only with the
  // fractions.
  settings.operatorUnchanged = desc_.kind == FluidKind::Smoke && !pressureOperatorStale_;
  pressureOperatorStale_ = false;
  st.projectionPrepared = true;
  st.projectionFailed = !phaseOk(Phase::Pressure, "pressure projection",
                                 st.projection.prepare(*st.input.tasks, grid_, fractions_, st.h, desc_.density,
                                                       settings, pressure_, liquidPhi(),
                                                       slabSamples(FluidSlice::PressureUpdate)));
  return st.projectionFailed ||
         withSliceStop([&](const Deadline* stop) { return st.projection.advanceSetup(stop); });
}

bool FluidActor::iterateProjection() {
  StepInProgress& st = *step_;
  if (st.projectionFailed || st.projection.solved()) return true;
  ++st.stats->phase(Phase::Pressure).iterations;
  return st.projection.iterate();
}

bool FluidActor::finishProjectionSlice() {
  StepInProgress& st = *step_;
  if (!st.projectionFailed) {
    const bool done = withSliceStop([&](const Deadline* stop) { return st.projection.advanceFinish(stop); });
    sliceWork_ = st.projection.lastSliceSamples();
    if (!done) return false;
  }
  st.projectionPrepared = false;
  if (st.projectionFailed) return true;
  const PressureSolveStats ps = st.projection.stats();
  PhaseStats& phase = st.stats->phase(Phase::Pressure);
  phase.residual = std::max(phase.residual, ps.relativeResidual);
  st.stats->residual = std::max(st.stats->residual, ps.relativeResidual);
  return true;
}

void FluidActor::addSubstepLoads() {
  StepInProgress& st = *step_;
  sliceWork_ = 1;  // next to nothing unless a body takes a load (then a pass's worth)
  if (st.projectionFailed) return;  // no pressure of this sub-step to load anything with
  for (size_t c = 0; c < st.input.colliders.size(); ++c) {
    const FluidCollider& fc = st.input.colliders[c];
    if (!fc.dynamic || fc.geometry == nullptr) continue;
    sliceWork_ = 0;
    PressureLoad l;
    // The dynamic part: the body takes the hydrostatic one anew at each of its steps
    // (hydrostaticColliderLoad, hydrostaticSurfaceLoad).
    const LiquidWeight weight{liquidPhi(), st.input.gravity};
    if (fc.geometry->vertexVelocities.empty()) {
      l = pressureLoadOnCollider(grid_, fractions_, pressure_.poisson, pressure_.pressure.data(), desc_.density,
                                 *fc.geometry, fc.geometry->shape.translation, &weight);
      if (desc_.kinematicViscosity > 0.0) {
        RigidDrag drag;
        addViscousTractionOnCollider(grid_, viscosity_, desc_.density, st.h, *fc.geometry, &drag);
        st.rigidDragSum[c] += meanShare(drag, st.substeps);
      }
    } else {
      SurfacePressureLoad surface;
      surfacePressureLoad(*st.input.tasks, grid_, fractions_, pressure_.poisson, pressure_.pressure.data(),
                          liquidPhi(), desc_.density, *fc.geometry, &surface, &weight);
      l = surface.total;  // the pressure's, as a rigid body's: the traction goes in the drag
      if (desc_.kinematicViscosity > 0.0)
        addViscousTraction(grid_, viscosity_, desc_.density, st.h, *fc.geometry, &surface);
      addMeanOverSubsteps(surface.vertexForces, st.substeps, &st.vertexForceSum[c]);
      if (!surface.drag.empty()) {
        addMeanOverSubsteps(surface.drag.coefficient, st.substeps, &st.dragSum[c].coefficient);
        addMeanOverSubsteps(surface.drag.atRest, st.substeps, &st.dragSum[c].atRest);
      }
    }
    st.loadSum[c].force += l.force / st.substeps;
    st.loadSum[c].torque += l.torque / st.substeps;
    st.loadSum[c].addedMass += l.addedMass / st.substeps;
  }
}

PressureLoad FluidActor::hydrostaticColliderLoad(const Vec3& gravity, const PreparedCollider& collider) const {
  const bool liquid = desc_.kind == FluidKind::Liquid && !shown_.levelSet.empty();
  return hydrostaticLoadOnCollider(grid_, liquid ? shown_.levelSet.data() : nullptr, desc_.density, gravity, collider,
                                   collider.shape.translation);
}

void FluidActor::hydrostaticSurfaceLoad(TaskSystem& tasks, const Vec3& gravity, const Array<Eigen::Vector3d>& vertices,
                                        const Array<Eigen::Vector3i>& triangles, Array<Vec3>* vertexForces) const {
  const bool liquid = desc_.kind == FluidKind::Liquid && !shown_.levelSet.empty();
  surfaceHydrostaticLoad(tasks, grid_, liquid ? shown_.levelSet.data() : nullptr, desc_.density, gravity, vertices,
                         triangles, vertexForces);
}

void FluidActor::publish() {
  ++stepCount_;
  if (step_ == nullptr) {  // the initial state
    shown_.loads.clear();
    publishFields();
    return;
  }
  StepInProgress& st = *step_;
  if (injectedVelocityScale_ != 1.0) {
    for (Array<double>& u : grid_.velocity)
      for (double& v : u) v *= injectedVelocityScale_;
    injectedVelocityScale_ = 1.0;
  }
  // Non-finite or absurd speeds (the deformables' guard uses the same kind of bound) mean the
  // step blew up, and so does a kinetic energy beyond what the step's sources can explain
  // (fluid_step_energy.h). Its result is dropped: the fluid goes back to its last completed
  // step, which is what readers see already (its loads too), rather than hand NaNs or absurd
  // loads to the host and the bodies.
  speedAtEnd_ = maxSpeed(*st.input.tasks);
  if (!(std::isfinite(speedAtEnd_) && speedAtEnd_ <= kMaxFluidSpeed) || energyBlewUp()) {
    restorePublished();
    st.diverged = true;
    return;
  }
  kineticAtEnd_ = st.energy.kineticEnd;
  shown_.loads.clear();
  if (desc_.twoWayCoupling) {
    // The load is the mean over this step and acts during the next one (a delay of one step:
    // explicit coupling). Extrapolating it one step ahead to cancel the delay was tried and
    // made a floating box unstable (the pressure also carries the added-mass reaction, which
    // an extrapolation amplifies).
    for (size_t c = 0; c < st.input.colliders.size(); ++c)
      if (st.input.colliders[c].dynamic)
        shown_.loads.push_back(FluidColliderLoad{st.input.colliders[c].index1, st.input.colliders[c].generation,
                                                 st.loadSum[c], std::move(st.vertexForceSum[c]), st.seen[c],
                                                 std::move(st.dragSum[c]), st.rigidDragSum[c]});
  }
  publishFields();
}

bool FluidActor::editFields(const std::function<void(EditableFields&)>& edit) {
  if (stepInProgress()) return false;
  EditableFields fields{grid_, smokeDensity_, temperature_, phi_};
  edit(fields);
  speedAtEnd_ = kineticAtEnd_ = -1.0;  // the next step measures the edited velocities
  publishFields();
  return true;
}

void FluidActor::restorePublished() {
  grid_ = shown_.grid;
  grid_.sides = desc_.sides;  // a change of sides taken when the step began stays
  smokeDensity_ = shown_.smokeDensity;
  temperature_ = shown_.temperature;
  phi_ = shown_.levelSet;
  pressure_.pressure = shown_.pressure;
  cellWeights_ = shown_.cellWeights;
  speedAtEnd_ = kineticAtEnd_ = -1.0;  // the next step measures the restored velocities
}

void FluidActor::publishFields() {
  shown_.grid = grid_;
  shown_.smokeDensity = smokeDensity_;
  shown_.temperature = temperature_;
  shown_.levelSet = phi_;
  shown_.pressure = pressure_.pressure;
  shown_.cellWeights = cellWeights_;
}

bool FluidActor::runsSlabs(FluidSlice kind) {
  switch (kind) {
    case FluidSlice::Fractions:
    case FluidSlice::SurfaceFractions:
    case FluidSlice::CellWeights:
    case FluidSlice::AdvectVelocity:
    case FluidSlice::AdvectScalars:
    case FluidSlice::LevelSet:
    case FluidSlice::Forces:
    case FluidSlice::PressureUpdate:
    case FluidSlice::Extrapolate: return true;
    default: return false;  // the projection's setup also has pieces that are not slabs
  }
}

Phase FluidActor::phaseOf(FluidSlice kind) {
  switch (kind) {
    case FluidSlice::Fractions:
    case FluidSlice::CellWeights:
    case FluidSlice::Plan: return Phase::Fractions;
    case FluidSlice::SurfaceFractions:
    case FluidSlice::Loads: return Phase::Coupling;
    case FluidSlice::AdvectVelocity:
    case FluidSlice::AdvectScalars: return Phase::Advect;
    case FluidSlice::Sources:
    case FluidSlice::Forces: return Phase::Forces;
    case FluidSlice::Viscosity: return Phase::Viscosity;
    case FluidSlice::PressureSetup:
    case FluidSlice::PressureIteration:
    case FluidSlice::PressureUpdate: return Phase::Pressure;
    case FluidSlice::LevelSet:
    case FluidSlice::Extrapolate:
    case FluidSlice::Publish:
    case FluidSlice::Count: break;
  }
  return Phase::Surface;
}

void FluidActor::invalidateDerived() {
  fractionsChanged_ = pressureOperatorStale_ = true;
  for (ColliderSnapshot& c : snapshots_)
    if (c.generation & kDeformableSolidBit) c.surfaceMoves = kUnknownMoves;
}

FluidState FluidActor::saveState() const {
  FluidState s;
  for (int a = 0; a < 3; ++a) {
    s.velocity[a] = grid_.velocity[a];
    s.open[a] = fractions_.open[a];
    s.solidVelocity[a] = fractions_.solidVelocity[a];
    s.extrapolationMark[a] = extrapolation_.mark[a];
  }
  s.smokeDensity = smokeDensity_;
  s.temperature = temperature_;
  s.levelSet = phi_;
  s.pressure = pressure_.pressure;
  s.cellWeights = cellWeights_;
  for (const ColliderSnapshot& c : snapshots_)
    s.fractionColliders.push_back(FluidColliderPose{c.index1, c.generation, c.bounds.lo, c.bounds.hi, c.rotation,
                                                    c.translation, c.linearVelocity, c.angularVelocity});
  s.fractionsValid = fractionsValid_;
  s.speedAtEnd = speedAtEnd_;
  s.kineticAtEnd = kineticAtEnd_;
  s.targetVolume = targetVolume_;
  for (const FluidColliderLoad& l : shown_.loads)
    s.loads.push_back(
        FluidColliderLoadState{l.index1, l.generation, l.load, l.vertexForces, l.seen, l.drag, l.rigidDrag});
  s.solidMotions = solidMotions_.lastStep();
  s.stepCount = stepCount_;
  s.lastStepSlices = lastStepSlices_;
  for (const SliceSizer& sizer : slabs_) s.slabs.push_back(sizer.state());
  s.sliceCostsMs = job_.costs();
  s.work = work_;
  s.schedule = schedule_;
  return s;
}

void FluidActor::restoreState(FluidState&& s) {
  job_.reset();
  step_.reset();
  for (int a = 0; a < 3; ++a) {
    grid_.velocity[a] = std::move(s.velocity[a]);
    fractions_.open[a] = std::move(s.open[a]);
    fractions_.solidVelocity[a] = std::move(s.solidVelocity[a]);
    extrapolation_.mark[a] = std::move(s.extrapolationMark[a]);
  }
  smokeDensity_ = std::move(s.smokeDensity);
  temperature_ = std::move(s.temperature);
  phi_ = std::move(s.levelSet);
  pressure_.pressure = std::move(s.pressure);
  cellWeights_ = std::move(s.cellWeights);
  snapshots_.clear();
  for (const FluidColliderPose& c : s.fractionColliders)
    snapshots_.push_back(ColliderSnapshot{c.index1, c.generation, Aabb{c.lo, c.hi}, c.rotation, c.translation,
                                          c.linearVelocity, c.angularVelocity,
                                          (c.generation & kDeformableSolidBit) ? kUnknownMoves : 0});
  fractionsValid_ = s.fractionsValid;
  invalidateDerived();
  speedAtEnd_ = s.speedAtEnd;
  kineticAtEnd_ = s.kineticAtEnd;
  targetVolume_ = s.targetVolume;
  publishFields();
  shown_.loads.clear();
  for (FluidColliderLoadState& l : s.loads)
    shown_.loads.push_back(
        FluidColliderLoad{l.index1, l.generation, l.load, std::move(l.vertexForces), l.seen, std::move(l.drag),
                          l.rigidDrag});
  solidMotions_.restore(std::move(s.solidMotions));
  stepCount_ = s.stepCount;
  surfaceStep_ = ~uint64_t(0);
  lastStepSlices_ = s.lastStepSlices;
  for (size_t k = 0; k < slabs_.size(); ++k) slabs_[k].restore(s.slabs[k]);
  job_.restoreCosts(s.sliceCostsMs);
  work_ = s.work;
  schedule_ = s.schedule;
}

}  // namespace vp

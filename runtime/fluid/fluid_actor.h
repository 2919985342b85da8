// A fluid actor: smoke or liquid on a MAC grid in a box domain, with the world's colliders as
// cut-cell solid boundaries (exact face fractions) and, optionally, two-way coupling to the
// dynamic ones.
//
// One step of dt is a list of stages, run as slices (core/sliced_job.h) that the world may
// spread over several frames; readers (fields, velocities, surface, loads) see the last
// completed step, switched in one place (publish) when a step completes. The stages never
// read a clock, so a step gives bitwise the same result however it is sliced:
//   Fractions  face fractions brought up to date where colliders moved (incremental), and
//              the faces of cells that a thin collider splits closed except around the
//              cell's main piece (cut_cell_components.h)
//   Plan       sub-steps of dt/n, n = ceil(max speed * dt / (cfl h)) capped at maxSubsteps;
//   then per sub-step:
//   Advect     velocity (and smoke density/temperature, or the liquid level set); smoke is
//              sampled through open faces only (advection.h)
//   Sources    emitters, drains (timed as Forces); liquid: level-set upkeep (Surface phase)
//   Viscosity  only when kinematicViscosity > 0: implicit diffusion of the velocity
//              (viscosity.h). Before the forces: diffusing u + g dt against no-slip solids
//              slows the uniform velocity gravity adds next to them, which the projection
//              then turns into a spurious pressure; the advected velocity of a fluid at rest
//              is 0 and stays so. Before the projection, so what it leaves is made
//              divergence-free.
//   Forces     buoyancy + vorticity confinement + dissipation (smoke) or gravity (liquid)
//   Pressure   cut-cell projection: setup in slabs, one slice per CG iteration (to the
//              tolerance or pressureMaxIterations, never cut by time), velocity update in
//              slabs, loads (on a dynamic collider its force and torque, pressure_forces.h;
//              on a deformable's surface the force on each vertex, surface_pressure_load.h)
// Passes over the grid (fractions, advection, level-set upkeep, forces, extrapolation, the
// projection's setup and update) run in slabs, one slab per slice, of at most
// solver.samplesPerSlice samples; under a budget, of a number of samples that starts small
// and follows the slices' measured cost toward the budget's target slice length
// (core/slice_sizer.h).
//   Surface    liquid: velocity extrapolation
//   Publish    divergence guard (a diverged step is dropped: the fluid goes back to the last
//              completed step), then what readers see becomes this step's result
// The pressure loads on dynamic colliders, averaged over the sub-steps, are those of the last
// completed step (loads()); the world applies them during the rigid steps that follow.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/allocator.h"
#include "collide/face_coverage.h"
#include "core/budget_clock.h"
#include "core/slice_sizer.h"
#include "core/sliced_job.h"
#include "core/task_system.h"
#include "core/work_progress.h"
#include "fluid/advection/advection.h"
#include "fluid/fluid_desc.h"
#include "fluid/fluid_step_energy.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/pressure_projection.h"
#include "fluid/smoke_forces.h"
#include "fluid/solids/face_fraction_field.h"
#include "fluid/solids/pressure_forces.h"
#include "fluid/solids/solid_motion_history.h"
#include "fluid/surface/level_set_redistance.h"
#include "fluid/surface/level_set_solid_extension.h"
#include "fluid/surface/liquid_volume.h"
#include "fluid/surface/marching_cubes.h"
#include "fluid/surface/velocity_extrapolation.h"
#include "fluid/viscosity.h"
#include "frame_plan.h"
#include "snapshot/actor_states.h"
#include "step_stats.h"

namespace vp {

// A fluid's solids are the world's colliders and the deformables' surfaces (deforming
// surfaces, collide/face_coverage.h). A deformable's handle is told from a collider's by this
// bit of its generation (handles of either kind keep their generations below it).
constexpr uint32_t kDeformableSolidBit = 1u << 30;

struct FluidCollider {
  uint32_t index1 = 0, generation = 0;  // identifies the solid across steps
  const PreparedCollider* geometry = nullptr;
  // Keeps `geometry` as it was while a step spanning several frames uses it (the collider
  // copies its geometry before moving it while it is shared); null when the caller keeps the
  // geometry unchanged until the step completes.
  std::shared_ptr<const PreparedCollider> keep;
  bool dynamic = false;  // receives pressure loads when two-way coupling is on
  SolidMotion motion;    // the solid's motion as a rigid body's now (solids/solid_motion_history.h)
};

struct FluidStepInput {
  double dt = 1.0 / 60.0;
  Vec3 gravity = Vec3::Zero();
  TaskSystem* tasks = nullptr;
  std::vector<FluidCollider> colliders;
};

struct FluidColliderLoad {
  uint32_t index1 = 0, generation = 0;
  // The pressure's load less its hydrostatic part at the step's positions
  // (FluidActor::hydrostaticColliderLoad and hydrostaticSurfaceLoad, which the body takes anew
  // at each of its steps); torque about the collider's origin (a deformable's: about the world
  // origin).
  PressureLoad load;
  // A deformable surface's: the force on each of its vertices less its hydrostatic part there
  // (FluidActor::hydrostaticSurfaceLoad, which the body takes anew at each of its steps).
  Array<Vec3> vertexForces;
  // The change of the solid's motion that the step saw (solids/solid_motion_history.h): the
  // load holds the fluid's reaction to it, -load.addedMass x seen.linear.
  SolidAcceleration seen;
  // The viscous traction (solids/viscous_traction.h), apart from the pressure's load: a
  // deformable surface's on its vertices, a rigid body's on the whole.
  VertexDrag drag;
  RigidDrag rigidDrag;
};

// The liquid's free surface, oriented out of the liquid.
struct FluidSurface {
  Array<Vec3> positions, normals;
  Array<Eigen::Vector3i> triangles;
};

// Which slices may run now: while the share leaves room for the next slice's expected cost,
// and in any case until minWork has been done (the plan's progress floor, in the units of
// core/work_progress.h).
struct SliceBudget {
  Deadline share;
  int64_t minWork = 0;
  double targetSliceMs = 0.0;  // what a slab slice should last (FramePlan::targetSliceMs); 0: any
};

// The kinds of slice a fluid step is made of (their measured costs are kept per kind).
enum class FluidSlice : int {
  Fractions, Plan, AdvectVelocity, AdvectScalars, Sources, LevelSet, Viscosity, Forces,
  PressureSetup, PressureIteration, PressureUpdate, Extrapolate, Publish,
  SurfaceFractions, CellWeights, Loads, Count
};

class FluidActor {
 public:
  static Status create(FluidDesc desc, TaskSystem& tasks, std::unique_ptr<FluidActor>* out);

  // One whole step, unbudgeted. Fills stats; `loads` receives the pressure loads on dynamic
  // colliders (may be null).
  void step(const FluidStepInput& input, ActorStats* stats, std::vector<FluidColliderLoad>* loads);

  // The step in slices: begins a step of `input` when none is in progress, then runs slices
  // as `budget` allows. Adds what ran to `stats` (phases, slices, iterations, progress).
  // Returns true when a step completed (its results are then published).
  bool advance(const FluidStepInput& input, const SliceBudget& budget, ActorStats* stats);
  // After an exception out of advance() (out of memory): the step in progress is dropped, the
  // fluid is its last completed step again, and what the step derives is rebuilt next time.
  void abandonStep();
  bool stepInProgress() const { return !job_.done(); }

  // The fields as a step works on them, for edits outside a step (initial conditions).
  struct EditableFields {
    MacGrid& grid;
    Array<double>& smokeDensity;
    Array<double>& temperature;
    Array<double>& levelSet;
  };
  // Runs `edit` on the working fields; readers see the edit at once. Refused (false) while a
  // step is in progress: the step would overwrite it.
  bool editFields(const std::function<void(EditableFields&)>& edit);
  // The fraction of the step in progress done so far (by work, against the work a step is
  // expected to take); 0 when none is in progress.
  double progress() const;
  // The work of the step in progress, or of the steps before (core/work_progress.h): samples
  // for slab slices, a pass over the grid (its cell count) for any other slice.
  const WorkProgress& stepWork() const { return work_; }
  // Slices of the last completed step (0 before the first).
  int lastStepSlices() const { return lastStepSlices_; }

  // What evolves from step to step (snapshot/actor_states.h). saveState needs no step in
  // progress (the world completes one first); restoreState drops a step in progress and takes
  // a state read for this fluid (its sizes checked), and cannot fail. What the state derives
  // (the pressure operator, the open-face masks, the surface mesh) is rebuilt when next needed.
  FluidState saveState() const;
  void restoreState(FluidState&& state);
  // What the fluid derives from its state (the pressure operator, the open-face masks) is
  // rebuilt when next needed. A restore does this; a save does it too, so that both go on
  // alike, in time too (a rebuild costs slices under a budget).
  // A deformable's surface is taken as moved since (its count of moves is not in the state).
  void invalidateDerived();

  // What readers see: the last completed step.
  const FluidDesc& desc() const { return desc_; }
  // From the next step that begins (a step in progress keeps the colliders it began with).
  void setCollisionFilter(const CollisionFilter& filter) { desc_.filter = filter; }
  // Test hook: the next fallible part of `phase` fails as if its solver had (see phaseOk).
  void injectPhaseFailureForTesting(Phase phase) { injectedFailure_ = phase; }
  // Test hook: the next step's velocities are scaled by `factor` just before its divergence
  // guard, as a stage that put energy in unasked would leave them.
  void injectVelocityScaleForTesting(double factor) { injectedVelocityScale_ = factor; }
  // The controls as last set (those waiting for the next step included); a change is
  // validated (on failure nothing changes) and takes effect when the next step begins.
  FluidControls controls() const;
  Status setControls(const FluidControls& controls);
  ActorSchedule& schedule() { return schedule_; }
  // The longest slice run by the last advance().
  double maxSliceMs() const { return maxSliceMs_; }
  const MacGrid& grid() const { return shown_.grid; }
  Aabb domainBounds() const;  // the box the grid spans
  const Array<double>& smokeDensity() const { return shown_.smokeDensity; }
  const Array<double>& temperature() const { return shown_.temperature; }
  const Array<double>& levelSet() const { return shown_.levelSet; }
  const Array<double>& pressure() const { return shown_.pressure; }
  Vec3 sampleVelocity(const Vec3& x) const { return shown_.grid.sampleVelocity(x); }
  // The pressure loads of the last completed step on dynamic colliders.
  const std::vector<FluidColliderLoad>& loads() const { return shown_.loads; }
  // The hydrostatic part of the load on a rigid collider (torque about its origin) under the
  // last completed step's free surface (solids/pressure_forces.h); zero for smoke.
  PressureLoad hydrostaticColliderLoad(const Vec3& gravity, const PreparedCollider& collider) const;
  // The same on a closed surface (its vertices, outward triangles; solids/surface_pressure_load.h).
  void hydrostaticSurfaceLoad(TaskSystem& tasks, const Vec3& gravity, const Array<Eigen::Vector3d>& vertices,
                              const Array<Eigen::Vector3i>& triangles, Array<Vec3>* vertexForces) const;
  // Total smoke (density integrated over the domain, density units * m^3).
  double totalSmoke() const;
  // Liquid volume in m^3 (0 for smoke).
  double liquidVolume() const;
  // Built on the first request after a step (empty for smoke). A failed extraction returns
  // its reason (the last error; injectPhaseFailureForTesting(Phase::Surface) makes the next
  // one fail) and is not kept: the next request tries again.
  Status surface(const FluidSurface** out);
  uint64_t stepCount() const { return stepCount_; }
  // The working fractions (those of the step in progress, or of the last one).
  const FaceFractionField& fractions() const { return fractions_; }

 private:
  explicit FluidActor(FluidDesc desc) : desc_(std::move(desc)) {}
  void beginStep(const FluidStepInput& input);
  // The stages (see the top of this file).
  void planFractionUpdate();
  // One slice of a planned pass list per call (the rigid colliders', the deformables', the
  // liquid's cell weights after both); true when it is done.
  bool runFractionPassesSlice(SlabPasses& passes, FluidSlice kind);
  void finishFractionUpdate();
  void planSubsteps();
  void planEnergyBound(double solidSpeed);
  // Whether the step's kinetic energy rose beyond its sources' bound (logs it when so).
  bool energyBlewUp();
  void queueSubstep(int sub);
  // One slice of the sub-step's advection per call; true when the last is done.
  bool advectVelocitySlab();
  bool advectScalarsSlab();
  void applySources();
  // Solid extension, redistancing, volume correction: one slice per call; true when done.
  bool keepLevelSetHealthySlice();
  void diffuseVelocity();
  // The sub-step's body forces (smoke_forces.h): planned as passes, then one slice per call;
  // true when done.
  void planForces();
  bool applyForcesSlice();
  // The projection's setup, CG iterations and velocity update (with the loads): one slice per
  // call; true when that part is done.
  bool setUpProjectionSlice();
  bool iterateProjection();
  bool finishProjectionSlice();
  VelocityExtrapolationSettings extrapolationSettings() const;
  void extrapolateLiquidVelocity();  // whole, for the first step's start
  bool extrapolateLiquidVelocitySlice();
  void publish();
  void publishFields();
  // The working fields back to the last completed step's (after a diverged step).
  void restorePublished();
  static Phase phaseOf(FluidSlice kind);
  static bool runsSlabs(FluidSlice kind);

  // The fractions' update: `passes` for rigid colliders (and everything when the set of
  // solids changed), `surfacePasses` for deformables that moved (the coupling's part).
  Status addFractionUpdatePasses(SlabPasses& passes, SlabPasses& surfacePasses);
  double maxSpeed(TaskSystem& tasks) const;
  const double* liquidPhi() const { return desc_.kind == FluidKind::Liquid ? phi_.data() : nullptr; }

  struct ColliderSnapshot {
    uint32_t index1, generation;
    Aabb bounds;
    Eigen::Quaterniond rotation;
    Eigen::Vector3d translation, linearVelocity, angularVelocity;
    uint64_t surfaceMoves;  // a deforming surface's (0 for a collider); kUnknownMoves after a save or restore
  };
  static constexpr uint64_t kUnknownMoves = ~uint64_t(0);
  // The loads of the sub-step just projected on the input's dynamic solids, added to the step's means.
  void addSubstepLoads();
  // The liquid's level-set upkeep in progress (one sub-step's).
  struct LevelSetUpkeep {
    enum Stage { Extend, Extending, Redistancing, Correcting } stage = Extend;
    SolidExtensionRun extension;
    RedistanceRun redistance;
    VolumeCorrectionRun volume;
  };
  // What the step in progress carries from stage to stage.
  struct StepInProgress {
    FluidStepInput input;
    double speed = 0.0;  // bound on anything's speed in this step
    int substeps = 1;
    double h = 0.0;      // sub-step
    std::vector<PressureLoad> loadSum;  // per input collider
    std::vector<SolidAcceleration> seen;  // per input collider
    std::vector<Array<Vec3>> vertexForceSum;  // per input collider (deforming surfaces only)
    std::vector<VertexDrag> dragSum;           // per input collider (deforming surfaces only)
    std::vector<RigidDrag> rigidDragSum;       // per input collider (rigid ones only)
    std::vector<const PreparedCollider*> fractionColliders;  // the input's, with geometry
    SlabPasses fractionUpdate, surfaceFractionUpdate, cellWeightUpdate;
    SlabPasses forces;  // the sub-step's body forces
    VelocityAdvectionSlices velocityAdvection;
    ScalarAdvectionSlices scalarAdvection;
    bool advecting = false;  // an advection pass list is prepared and running
    LevelSetUpkeep levelSet;
    VelocityExtrapolationRun extrapolation;
    bool extrapolating = false;
    PressureProjectionRun projection;
    bool projectionPrepared = false;  // for the sub-step's projection in progress
    bool projectionFailed = false;
    bool diverged = false;
    // The divergence guard's energy account (fluid_step_energy.h): the start's kinetic
    // energy, the largest body-force acceleration, the fastest solid or emitter.
    StepEnergy energy;
    double energyAcceleration = 0.0, energyBoundarySpeed = 0.0;
    ActorStats* stats = nullptr;  // of the frame now running
  };
  // What readers see (the last completed step).
  struct ShownState {
    MacGrid grid;
    Array<double> smokeDensity, temperature, levelSet, pressure, cellWeights;
    std::vector<FluidColliderLoad> loads;
  };

  FluidDesc desc_;
  std::optional<FluidControls> pendingControls_;  // applied by beginStep
  std::optional<Phase> injectedFailure_;
  double injectedVelocityScale_ = 1.0;
  // One fallible part of a step's phase: on failure (or an injected one) logs it, marks the
  // phase failed in the frame's stats, and returns false; the step goes on without that part.
  bool phaseOk(Phase phase, const char* what, Status status);
  MacGrid grid_;
  FaceFractionField fractions_;
  std::vector<ColliderSnapshot> snapshots_;  // the colliders the fractions were computed for
  SolidMotionHistory solidMotions_;  // as the steps took them, for their loads
  bool fractionsValid_ = false;
  bool fractionsChanged_ = true;  // since the advection's open-face masks were built
  bool pressureOperatorStale_ = true;  // the fractions changed since the last projection
  double speedAtEnd_ = -1.0;  // largest face speed after the last step; < 0 before the first
  double kineticAtEnd_ = -1.0;  // kinetic energy after the last step (fluid_step_energy.h); < 0: unknown
  Array<double> smokeDensity_, temperature_, phi_;
  PressureState pressure_;
  AdvectionWorkspace advection_;
  CellOpenFaces openFaces_;  // smoke: which faces advection may interpolate through
  VorticityWorkspace vorticity_;
  ViscosityWorkspace viscosity_;
  TaskSystem* tasks_ = nullptr;  // the world's, for on-request work (surface extraction)
  std::vector<SliceSizer> slabs_;  // per FluidSlice kind
  // Unbudgeted, the slabs are as large as the solver settings allow.
  int64_t slabSamples(FluidSlice kind) const {
    return sliceTargetMs_ > 0.0 ? slabs_[static_cast<size_t>(kind)].samples() : desc_.solver.samplesPerSlice;
  }
  double sliceTargetMs_ = 0.0;  // of the advance() running
  Clock sliceClock_;            // its clock
  // run(stop): budgeted, stop ends a slab slice once it has run for its target
  // (SlabPasses::runSlice); unbudgeted, stop is null.
  template <class Run>
  bool withSliceStop(const Run& run) const {
    if (!(sliceTargetMs_ > 0.0)) return run(nullptr);
    const Deadline stop(sliceClock_, sliceTargetMs_);
    return run(&stop);
  }
  // Liquid: the volume the level set must keep (initial + emitted - drained), the cells'
  // open fractions that weight it, and the level-set workspaces.
  double targetVolume_ = 0.0;
  Array<double> cellWeights_;
  Array<int64_t> solidCells_;
  RedistanceWorkspace redistance_;
  VelocityExtrapolationState extrapolation_;
  SlicedJob job_{static_cast<int>(FluidSlice::Count)};
  std::unique_ptr<StepInProgress> step_;
  int lastStepSlices_ = 0;
  WorkProgress work_;
  int64_t sliceWork_ = 0;  // samples the running slice did (0: not a slab slice)
  double maxSliceMs_ = 0.0;
  ActorSchedule schedule_;  // the frame plan's state of this fluid
  ShownState shown_;
  FluidSurface surface_;
  MarchingCubesWorkspace marchingCubes_;
  uint64_t stepCount_ = 0, surfaceStep_ = ~uint64_t(0);
};

}  // namespace vp

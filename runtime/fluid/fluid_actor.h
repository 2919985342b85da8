// A fluid actor: smoke or liquid on a MAC grid in a box domain, with the world's colliders as
// cut-cell solid boundaries (exact face fractions) and, optionally, two-way coupling to the
// dynamic ones.
//
// One world step of dt:
//   Fractions  face fractions brought up to date where colliders moved (incremental), and
//              the faces of cells that a thin collider splits closed except around the
//              cell's main piece (cut_cell_components.h)
//   then sub-steps of dt/n, n = ceil(max speed * dt / (cfl h)) capped at maxSubsteps:
//   Advect     velocity (and smoke density/temperature, or the liquid level set); smoke is
//              sampled through open faces only (advection.h)
//   Sources    emitters, drains (timed as Forces); liquid: level-set upkeep (Surface phase)
//   Viscosity  only when kinematicViscosity > 0: implicit diffusion of the velocity
//              (viscosity.h), budgeted with a third of the sub-step's share. Before the
//              forces: diffusing u + g dt against no-slip solids slows the uniform velocity
//              gravity adds next to them, which the projection then turns into a spurious
//              pressure (measured: a half-density box floated 60% submerged instead of 50%);
//              the advected velocity of a fluid at rest is 0 and stays so. Before the
//              projection, so what it leaves is made divergence-free.
//   Forces     buoyancy + vorticity confinement + dissipation (smoke) or gravity (liquid)
//   Pressure   cut-cell projection, budgeted (each sub-step gets an equal share of what is
//              left of the actor's deadline), warm-started from the last pressure
//   Surface    liquid: redistancing, volume correction, velocity extrapolation
// The pressure loads on dynamic colliders, averaged over the sub-steps, are reported in
// FluidStepResult for the world to apply during the next rigid step.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "collide/face_coverage.h"
#include "core/budget_clock.h"
#include "core/task_system.h"
#include "fluid/advection.h"
#include "fluid/face_fraction_field.h"
#include "fluid/fluid_desc.h"
#include "fluid/level_set_redistance.h"
#include "fluid/marching_cubes.h"
#include "fluid/velocity_extrapolation.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure_forces.h"
#include "fluid/pressure_projection.h"
#include "fluid/smoke_forces.h"
#include "fluid/viscosity.h"
#include "step_stats.h"

namespace vp {

struct FluidCollider {
  uint32_t index1 = 0, generation = 0;  // identifies the collider across steps
  const PreparedCollider* geometry = nullptr;
  bool dynamic = false;  // receives pressure loads when two-way coupling is on
};

struct FluidStepInput {
  double dt = 1.0 / 60.0;
  Vec3 gravity = Vec3::Zero();
  Deadline deadline;
  TaskSystem* tasks = nullptr;
  std::vector<FluidCollider> colliders;
};

struct FluidColliderLoad {
  uint32_t index1 = 0, generation = 0;
  PressureLoad load;  // torque about the collider's origin
};

// The liquid's free surface, oriented out of the liquid.
struct FluidSurface {
  std::vector<Vec3> positions, normals;
  std::vector<Eigen::Vector3i> triangles;
};

class FluidActor {
 public:
  static Status create(FluidDesc desc, TaskSystem& tasks, std::unique_ptr<FluidActor>* out);

  // Fills stats; `loads` receives the pressure loads on dynamic colliders (may be null).
  void step(const FluidStepInput& input, ActorStats* stats, std::vector<FluidColliderLoad>* loads);

  const FluidDesc& desc() const { return desc_; }
  const MacGrid& grid() const { return grid_; }
  const FaceFractionField& fractions() const { return fractions_; }
  const std::vector<double>& smokeDensity() const { return smokeDensity_; }
  const std::vector<double>& temperature() const { return temperature_; }
  const std::vector<double>& levelSet() const { return phi_; }
  const std::vector<double>& pressure() const { return pressure_.pressure; }
  Vec3 sampleVelocity(const Vec3& x) const { return grid_.sampleVelocity(x); }
  // Total smoke (density integrated over the domain, density units * m^3).
  double totalSmoke() const;
  // Liquid volume in m^3 (0 for smoke).
  double liquidVolume() const;
  // Built on the first request after a step (empty for smoke).
  const FluidSurface& surface();
  uint64_t stepCount() const { return stepCount_; }

 private:
  explicit FluidActor(FluidDesc desc) : desc_(std::move(desc)) {}
  Status updateFractions(const std::vector<FluidCollider>& colliders);
  double maxSpeed(TaskSystem& tasks) const;
  Aabb domainBounds() const;
  // Advection, emitters and drains, and the liquid's level-set upkeep. maxDisplacement: the
  // farthest the flow (and colliders) move anything in this sub-step.
  void advectAndSource(TaskSystem& tasks, double dt, double maxDisplacement, ActorStats* stats,
                       const Deadline& deadline);
  // Gravity (liquid) or buoyancy, vorticity confinement and dissipation (smoke). Without
  // viscosity the two together do what they did as one (the liquid's level-set upkeep never
  // reads the velocity), so the inviscid path is unchanged bit for bit.
  void applyForces(TaskSystem& tasks, const Vec3& gravity, double dt, ActorStats* stats, const Deadline& deadline);
  void keepLevelSetHealthy(TaskSystem& tasks);
  void extrapolateLiquidVelocity(TaskSystem& tasks);
  void diffuseVelocity(TaskSystem& tasks, double dt, const Deadline& deadline, ActorStats* stats);
  const double* liquidPhi() const { return desc_.kind == FluidKind::Liquid ? phi_.data() : nullptr; }

  struct ColliderSnapshot {
    uint32_t index1, generation;
    Aabb bounds;
    Eigen::Quaterniond rotation;
    Eigen::Vector3d translation, linearVelocity, angularVelocity;
  };

  FluidDesc desc_;
  MacGrid grid_;
  FaceFractionField fractions_;
  std::vector<ColliderSnapshot> snapshots_;  // the colliders the fractions were computed for
  bool fractionsValid_ = false;
  bool fractionsChanged_ = true;  // since the advection's open-face masks were built
  bool pressureOperatorStale_ = true;  // the fractions changed since the last projection
  double speedAtEnd_ = -1.0;  // largest face speed after the last step; < 0 before the first
  std::vector<double> smokeDensity_, temperature_, phi_;
  PressureState pressure_;
  AdvectionWorkspace advection_;
  CellOpenFaces openFaces_;  // smoke: which faces advection may interpolate through
  VorticityWorkspace vorticity_;
  ViscosityWorkspace viscosity_;
  FluidSurface surface_;
  TaskSystem* tasks_ = nullptr;  // the world's, for on-request work (surface extraction)
  // Liquid: the volume the level set must keep (initial + emitted - drained), the cells'
  // open fractions that weight it, and the level-set workspaces.
  double targetVolume_ = 0.0;
  std::vector<double> cellWeights_;
  std::vector<int64_t> solidCells_;
  RedistanceWorkspace redistance_;
  VelocityExtrapolationState extrapolation_;
  MarchingCubesWorkspace marchingCubes_;
  uint64_t stepCount_ = 0, surfaceStep_ = ~uint64_t(0);
};

}  // namespace vp

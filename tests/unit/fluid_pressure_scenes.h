// Pressure-solve scenes shared by the multigrid unit tests and the pressure benchmark
// (tests/bench includes this header): a unit-cube MAC grid of n^3 cells with colliders, a
// smooth non-solenoidal velocity, and the Poisson right-hand side it gives.
//   SmokeSphere      sphere of radius 0.2 (of the domain) below the centre, open top (+y)
//   TankPlateSphere  thin plate (0.02 thick) slanted 30 degrees and a sphere, open top
//   ClosedTank       the same colliders in a closed box: one floating (pure Neumann) region
//   LiquidTank       the same colliders, open top, liquid below y = 0.61: free-surface
//                    (ghost-fluid Dirichlet) faces inside the grid, air cells without rows
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <vector>

#include "collide/face_coverage.h"
#include "core/budget_clock.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/pressure/mic0_preconditioner.h"
#include "fluid/pressure/poisson_multigrid.h"
#include "fluid/pressure/pressure_projection.h"
#include "fluid/solids/face_fraction_field.h"
#include "linalg/conjugate_gradient.h"

namespace vp {
namespace testscene {

enum class PressureSceneKind { SmokeSphere, TankPlateSphere, ClosedTank, LiquidTank };

inline const char* sceneName(PressureSceneKind kind) {
  switch (kind) {
    case PressureSceneKind::SmokeSphere: return "smoke_sphere";
    case PressureSceneKind::TankPlateSphere: return "tank_plate_sphere";
    case PressureSceneKind::ClosedTank: return "closed_tank";
    case PressureSceneKind::LiquidTank: return "liquid_tank";
  }
  return "?";
}

struct PressureScene {
  MacGrid grid;
  FaceFractionField fractions;
  std::vector<PreparedCollider> colliders;
  std::vector<double> liquidPhi;  // LiquidTank only: the level set (negative in the liquid)
  CutCellPoisson poisson;
  std::vector<double> rhs;  // -netOutflow of the swirl velocity, 0 off fluid
};

inline ColliderShape sphere(const Eigen::Vector3d& centre, double radius) {
  ColliderShape s;
  s.kind = ShapeKind::Sphere;
  s.radius = radius;
  s.translation = centre;
  return s;
}

inline ColliderShape slantedPlate() {
  ColliderShape b;
  b.kind = ShapeKind::Box;
  b.halfExtents = Eigen::Vector3d(0.3, 0.01, 0.36);
  b.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 6.0, Eigen::Vector3d::UnitZ()));
  b.translation = Eigen::Vector3d(0.45, 0.42, 0.5);
  return b;
}

// A smooth velocity with components of order 1 and a nonzero divergence.
inline void fillSwirl(MacGrid& grid) {
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const Eigen::Vector3d x = grid.faceCentre(a, i, j, k);
          grid.velocity[a][grid.faceIndex(a, i, j, k)] =
              std::sin(3.0 * x.x() + a) * std::cos(2.0 * x.y() - a) + 0.5 * x.z() * x[a];
        }
  }
}

inline Status makePressureScene(TaskSystem& tasks, PressureSceneKind kind, int n, PressureScene* scene) {
  MacGridSpec spec;
  spec.h = 1.0 / n;
  spec.nx = spec.ny = spec.nz = n;
  std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                  DomainSide::Open, DomainSide::Wall, DomainSide::Wall};
  if (kind == PressureSceneKind::ClosedTank) sides[3] = DomainSide::Wall;
  VP_TRY(initMacGrid(spec, sides, &scene->grid));
  VP_TRY(initFaceFractionField(spec, &scene->fractions));
  std::vector<ColliderShape> shapes;
  if (kind == PressureSceneKind::SmokeSphere) {
    shapes.push_back(sphere(Eigen::Vector3d(0.5, 0.4, 0.5), 0.2));
  } else {
    shapes.push_back(slantedPlate());
    shapes.push_back(sphere(Eigen::Vector3d(0.7, 0.72, 0.45), 0.15));
  }
  scene->colliders.assign(shapes.size(), PreparedCollider{});
  std::vector<const PreparedCollider*> list;
  for (size_t s = 0; s < shapes.size(); ++s) {
    VP_TRY(prepareCollider(shapes[s], &scene->colliders[s]));
    list.push_back(&scene->colliders[s]);
  }
  VP_TRY(computeFaceFractions(list.data(), static_cast<int>(list.size()), &scene->fractions));
  fillSwirl(scene->grid);
  scene->liquidPhi.clear();
  if (kind == PressureSceneKind::LiquidTank) {
    scene->liquidPhi.resize(static_cast<size_t>(scene->grid.cellCount()));
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          scene->liquidPhi[scene->grid.cellIndex(i, j, k)] = scene->grid.cellCentre(i, j, k).y() - 0.61;
  }
  VP_TRY(buildCutCellPoisson(tasks, scene->grid, scene->fractions, &scene->poisson,
                             scene->liquidPhi.empty() ? nullptr : scene->liquidPhi.data()));
  scene->rhs.assign(static_cast<size_t>(scene->grid.cellCount()), 0.0);
  computeNetOutflow(tasks, scene->grid, scene->fractions, scene->poisson, scene->rhs.data());
  for (double& b : scene->rhs) b = -b;
  return Status::Ok;
}

// A clock that advances 1 ms on every read, so a budget lasts a fixed number of polls.
struct SteppingClock {
  double now = 0.0;
  static double read(void* self) {
    auto* c = static_cast<SteppingClock*>(self);
    c->now += 1e-3;
    return c->now;
  }
  Clock clock() { return Clock{&SteppingClock::read, this}; }
};

// The CG of projectVelocity on the scene's system, from p = 0, with the chosen preconditioner
// (built here, outside any timing the caller does around solve()).
struct SceneSolver {
  PressureSolver kind = PressureSolver::CutCellMgpcg;
  MultigridSettings multigrid;
  Mic0Preconditioner mic;
  PoissonMultigrid mg;
  CgWorkspace work;

  Status prepare(TaskSystem& tasks, const PressureScene& scene) {
    if (kind == PressureSolver::Mic0Pcg) return buildMic0Preconditioner(scene.poisson, Mic0Settings{}, &mic);
    MultigridSettings s = multigrid;
    s.coarsening = kind == PressureSolver::VoxelMgpcg ? MultigridCoarsening::Voxel : MultigridCoarsening::CutCell;
    return buildPoissonMultigrid(tasks, scene.poisson, scene.grid.sides, s, &mg);
  }

  void precondition(TaskSystem& tasks, const PressureScene& scene, const double* r, double* z) {
    if (kind == PressureSolver::Mic0Pcg) applyMic0Preconditioner(scene.poisson, mic, r, z);
    else applyPoissonMultigrid(tasks, scene.poisson, mg, r, z);
  }

  CgResult solve(TaskSystem& tasks, const PressureScene& scene, double tolerance, int maxIterations,
                 std::vector<double>* p) {
    p->assign(scene.rhs.size(), 0.0);
    LinearSystem system;
    system.size = static_cast<int64_t>(scene.rhs.size());
    system.apply = [&](const double* x, double* y) { applyCutCellPoisson(tasks, scene.poisson, x, y); };
    system.precondition = [&](const double* r, double* z) { precondition(tasks, scene, r, z); };
    system.filter = [&](double* v) { filterCutCellPoisson(tasks, scene.poisson, v); };
    CgSettings settings;
    settings.relativeTolerance = tolerance;
    settings.maxIterations = maxIterations;
    return solveConjugateGradient(tasks, system, scene.rhs.data(), p->data(), settings, Deadline(), work);
  }
};

// A scene and its cut-cell multigrid (SceneSolver's default settings), built.
inline Status makeSceneWithMultigrid(TaskSystem& tasks, PressureSceneKind kind, int n, PressureScene* scene,
                                     SceneSolver* solver) {
  VP_TRY(makePressureScene(tasks, kind, n, scene));
  return solver->prepare(tasks, *scene);
}

}  // namespace testscene
}  // namespace vp

// Pressure multigrid: coarse-level consistency, symmetry and positivity of the V-cycle,
// convergence rate and its independence of the resolution, agreement with MIC(0)-PCG.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "core/budget_clock.h"
#include "fluid/pressure/multigrid_coarsening.h"
#include "fluid_pressure_scenes.h"

namespace vp {
namespace {

using testscene::PressureScene;
using testscene::PressureSceneKind;
using testscene::SceneSolver;
using testscene::SteppingClock;

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

void makeScene(TaskSystem& tasks, PressureSceneKind kind, int n, PressureScene* scene) {
  ASSERT_EQ(testscene::makePressureScene(tasks, kind, n, scene), Status::Ok) << lastError();
}

// An empty open-top box: every fine fraction is 1, so both coarsenings must give the voxel
// operator at 2h (coupling 2, Dirichlet 2 on the top layer), and the Dirichlet part of a cell
// must come out of diagonal minus couplings.
TEST(FluidMultigrid, CoarseLevelsOfAnOpenBoxAreTheVoxelOperatorAtTwiceTheSpacing) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  MacGridSpec spec;
  spec.h = 0.1;
  spec.nx = 6;
  spec.ny = 6;
  spec.nz = 4;
  const std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                        DomainSide::Open, DomainSide::Wall, DomainSide::Wall};
  MacGrid grid;
  FaceFractionField fractions;
  ASSERT_EQ(initMacGrid(spec, sides, &grid), Status::Ok);
  ASSERT_EQ(initFaceFractionField(spec, &fractions), Status::Ok);
  CutCellPoisson fine, cut, voxel;
  ASSERT_EQ(buildCutCellPoisson(*tasks, grid, fractions, &fine), Status::Ok);
  EXPECT_EQ(dirichletPart(fine, static_cast<int64_t>(grid.cellIndex(2, 5, 1))), 1.0);
  EXPECT_EQ(dirichletPart(fine, static_cast<int64_t>(grid.cellIndex(2, 4, 1))), 0.0);
  ASSERT_EQ(coarsenCutCell(*tasks, fine, &cut), Status::Ok);
  ASSERT_EQ(coarsenVoxel(*tasks, fine, sides, &voxel), Status::Ok);
  EXPECT_EQ(cut.grid.nx, 3);
  EXPECT_EQ(cut.grid.ny, 3);
  EXPECT_EQ(cut.grid.nz, 2);
  EXPECT_DOUBLE_EQ(cut.grid.h, 0.2);
  for (int a = 0; a < 3; ++a) ASSERT_EQ(cut.coupling[a], voxel.coupling[a]) << "axis " << a;
  // Top coarse layer: 4 fine Dirichlet faces of fraction 1 under its open side, (4 * 1) / 2 = 2.
  for (size_t c = 0; c < cut.diagonal.size(); ++c) EXPECT_DOUBLE_EQ(cut.diagonal[c], voxel.diagonal[c]) << c;
  EXPECT_DOUBLE_EQ(cut.coupling[0][1 + 4 * (1 + 3 * 1)], 2.0);
  EXPECT_DOUBLE_EQ(dirichletPart(cut, 1 + 3 * (2 + 3 * 0)), 2.0);
  EXPECT_EQ(cut.regionFloating, Array<uint8_t>{0});
  EXPECT_EQ(cut.fluidCellCount, 18);
}

// A closed 4^3 box of unit size, every face open: the coarse face (1, 0, 0) has the fine
// u-faces x = 2h, (j, k) in {0, 1}^2 under it and x = h, 3h behind it.
void makeClosedBox4(MacGrid* grid, FaceFractionField* fractions) {
  MacGridSpec spec;
  spec.h = 0.25;
  spec.nx = spec.ny = spec.nz = 4;
  ASSERT_EQ(initMacGrid(spec, std::array<DomainSide, 6>{}, grid), Status::Ok);
  ASSERT_EQ(initFaceFractionField(spec, fractions), Status::Ok);
}

// A half-covered fine face layer must give weakened coarse couplings in the cut-cell hierarchy
// and full ones in the voxel hierarchy: the difference the thesis is about. Each fine column
// under the coarse face is the covered face in series with the open half faces behind it
// (multigrid_coarsening.h): 2 A / (1 + A), which is A only for A = 0 or 1.
TEST(FluidMultigrid, CutCellCoarseCouplingsFollowTheFineFractions) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  const std::array<DomainSide, 6> closed{};
  MacGrid grid;
  FaceFractionField fractions;
  makeClosedBox4(&grid, &fractions);
  // The u-faces at x = 2h: fractions 0.1, 0.3, 0.5, 0.7 under coarse face (1, 0, 0).
  const double open[4] = {0.1, 0.3, 0.5, 0.7};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j) fractions.open[0][grid.faceIndex(0, 2, j, k)] = open[j + 2 * k];
  CutCellPoisson fine, cut, voxel;
  ASSERT_EQ(buildCutCellPoisson(*tasks, grid, fractions, &fine), Status::Ok);
  ASSERT_EQ(coarsenCutCell(*tasks, fine, &cut), Status::Ok);
  ASSERT_EQ(coarsenVoxel(*tasks, fine, closed, &voxel), Status::Ok);
  const size_t face = 1;  // coarse u-face (1, 0, 0) in a 3 x 2 x 2 face array
  double columns = 0.0;
  for (double a : open) columns += 2.0 * a / (1.0 + a);
  EXPECT_DOUBLE_EQ(cut.coupling[0][face], 0.5 * columns);
  EXPECT_DOUBLE_EQ(voxel.coupling[0][face], 2.0);
  EXPECT_DOUBLE_EQ(cut.coupling[0][face + 6], 2.0);  // (1, 0, 1): fully open fine faces
  EXPECT_EQ(cut.regionFloating, Array<uint8_t>{1});
  EXPECT_DOUBLE_EQ(dirichletPart(cut, 0), 0.0);
}

// A solid layer inside the coarse cells (fine u-faces at x = h, behind the shared coarse face
// at x = 2h) closes the coarse coupling, though every fine face under the coarse face is open:
// averaging those alone would couple both sides of a thin plate on the coarse levels.
TEST(FluidMultigrid, CutCellCoarseCouplingsCloseBehindAThinSolid) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  MacGrid grid;
  FaceFractionField fractions;
  makeClosedBox4(&grid, &fractions);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j) fractions.open[0][grid.faceIndex(0, 1, j, k)] = 0.0;
  CutCellPoisson fine, cut;
  ASSERT_EQ(buildCutCellPoisson(*tasks, grid, fractions, &fine), Status::Ok);
  ASSERT_EQ(coarsenCutCell(*tasks, fine, &cut), Status::Ok);
  const size_t face = 1;  // coarse u-face (1, 0, 0) in a 3 x 2 x 2 face array
  EXPECT_DOUBLE_EQ(cut.coupling[0][face], 0.0);
  EXPECT_DOUBLE_EQ(cut.coupling[0][face + 6], 2.0);  // (1, 0, 1): nothing behind it
}

struct SymmetryCase {
  PressureSceneKind scene;
  PressureSolver solver;
  PoissonSmoother smoother;
};

// x . M y = y . M x for random filtered x, y (round-off only), and x . M x > 0. The V-cycle runs in
// single precision (poisson_multigrid.h), so "round-off" is float's: measured up to 3.1e-9 of
// |x| |M y| here. A cycle whose post-smoothing is not the adjoint of its pre-smoothing differs by
// 2.4e-6 to 5.7e-5 of it (measured on these scenes): the bound 1e-7 lies between the two.
TEST(FluidMultigrid, VCycleIsSymmetricAndPositive) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const SymmetryCase cases[] = {
      {PressureSceneKind::SmokeSphere, PressureSolver::CutCellMgpcg, PoissonSmoother::RedBlackGaussSeidel},
      {PressureSceneKind::SmokeSphere, PressureSolver::CutCellMgpcg, PoissonSmoother::DampedJacobi},
      {PressureSceneKind::ClosedTank, PressureSolver::CutCellMgpcg, PoissonSmoother::RedBlackGaussSeidel},
      {PressureSceneKind::TankPlateSphere, PressureSolver::VoxelMgpcg, PoissonSmoother::RedBlackGaussSeidel},
      {PressureSceneKind::ClosedTank, PressureSolver::VoxelMgpcg, PoissonSmoother::DampedJacobi},
      {PressureSceneKind::LiquidTank, PressureSolver::CutCellMgpcg, PoissonSmoother::RedBlackGaussSeidel},
      {PressureSceneKind::LiquidTank, PressureSolver::VoxelMgpcg, PoissonSmoother::RedBlackGaussSeidel},
  };
  for (const SymmetryCase& tc : cases) {
    SCOPED_TRACE(testing::Message() << testscene::sceneName(tc.scene) << " solver " << static_cast<int>(tc.solver)
                                    << " smoother " << static_cast<int>(tc.smoother));
    PressureScene scene;
    makeScene(*tasks, tc.scene, 20, &scene);
    SceneSolver solver;
    solver.kind = tc.solver;
    solver.multigrid.smoother = tc.smoother;
    ASSERT_EQ(solver.prepare(*tasks, scene), Status::Ok) << lastError();
    ASSERT_GE(solver.mg.levelCount(), 3);
    const size_t n = scene.rhs.size();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> x(n), y(n), mx(n), my(n);
    for (int trial = 0; trial < 3; ++trial) {
      for (size_t c = 0; c < n; ++c) {
        x[c] = u(rng);
        y[c] = u(rng);
      }
      filterCutCellPoisson(*tasks, scene.poisson, x.data());
      filterCutCellPoisson(*tasks, scene.poisson, y.data());
      solver.precondition(*tasks, scene, x.data(), mx.data());
      solver.precondition(*tasks, scene, y.data(), my.data());
      filterCutCellPoisson(*tasks, scene.poisson, mx.data());
      filterCutCellPoisson(*tasks, scene.poisson, my.data());
      const double scale = std::sqrt(dot(x, x) * dot(my, my));
      EXPECT_NEAR(dot(x, my), dot(y, mx), 1e-7 * scale);
      EXPECT_GT(dot(x, mx), 1e-3 * std::sqrt(dot(x, x) * dot(mx, mx)));
    }
  }
}

// The smoothers, transfers and coarse solves split work by fixed chunks and never let two
// workers race on a value, so one V-cycle gives bitwise the same result on 1, 3 or 8 workers.
TEST(FluidMultigrid, VCycleIsBitwiseIdenticalAcrossWorkerCounts) {
  std::vector<double> results[3];
  const int workers[3] = {1, 3, 8};
  for (int w = 0; w < 3; ++w) {
    auto tasks = TaskSystem::create(TaskHooks{}, workers[w]);
    PressureScene scene;
    makeScene(*tasks, PressureSceneKind::TankPlateSphere, 48, &scene);
    SceneSolver solver;
    ASSERT_EQ(solver.prepare(*tasks, scene), Status::Ok);
    results[w].resize(scene.rhs.size());
    solver.precondition(*tasks, scene, scene.rhs.data(), results[w].data());
  }
  EXPECT_TRUE(results[0] == results[1]);
  EXPECT_TRUE(results[0] == results[2]);
}

// Relative residual of the CG after each iteration, from p = 0 (CG is deterministic, so a run
// cut at k iterations has the k-th iterate of the full run).
std::vector<double> residualHistory(TaskSystem& tasks, const PressureScene& scene, SceneSolver& solver, int count) {
  std::vector<double> history, p;
  for (int k = 1; k <= count; ++k) history.push_back(solver.solve(tasks, scene, 1e-14, k, &p).relativeResidual);
  return history;
}

TEST(FluidMultigrid, ResidualDropsTenfoldEveryTwoIterationsPastSphere) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  PressureScene scene;
  makeScene(*tasks, PressureSceneKind::SmokeSphere, 64, &scene);
  SceneSolver solver;
  ASSERT_EQ(solver.prepare(*tasks, scene), Status::Ok) << lastError();
  const std::vector<double> history = residualHistory(*tasks, scene, solver, 12);
  for (size_t k = 0; k < history.size(); ++k) std::printf("    iteration %zu: residual %.3e\n", k + 1, history[k]);
  double previous = 1.0;  // the relative residual of p = 0
  for (size_t k = 1; k < history.size(); k += 2) {
    EXPECT_LE(history[k], 0.1 * previous) << "iterations " << k - 1 << " -> " << k + 1;
    previous = history[k];
    if (previous < 1e-12) break;
  }
}

int iterationsTo1e6(TaskSystem& tasks, PressureSceneKind kind, int n, PressureSolver which) {
  PressureScene scene;
  makeScene(tasks, kind, n, &scene);
  SceneSolver solver;
  solver.kind = which;
  EXPECT_EQ(solver.prepare(tasks, scene), Status::Ok) << lastError();
  std::vector<double> p;
  const CgResult result = solver.solve(tasks, scene, 1e-6, 500, &p);
  EXPECT_TRUE(result.converged);
  return result.iterations;
}

// The criterion (smoke past a sphere, at most 1.3x more iterations from 64^3 to 128^3)
// on 32^3 -> 64^3 to keep the unit tests quick; the benchmark reports 64, 128 and 192 for both
// scenes. The plate scene is left out here: its 0.02 thick plate is thinner than a 32^3 cell
// (partly open faces everywhere along it) and about one cell at 64^3, a change of regime rather
// than of resolution (7 -> 12 iterations measured; 12 -> 12 from 64^3 to 128^3).
TEST(FluidMultigrid, IterationCountGrowsAtMost30PercentPerRefinementPastSphere) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const PressureSceneKind kind = PressureSceneKind::SmokeSphere;
  const int coarse = iterationsTo1e6(*tasks, kind, 32, PressureSolver::CutCellMgpcg);
  const int fine = iterationsTo1e6(*tasks, kind, 64, PressureSolver::CutCellMgpcg);
  std::printf("    %d iterations at 32^3, %d at 64^3\n", coarse, fine);
  EXPECT_LE(fine, 1.3 * coarse);
}

// The liquid tank (plate, sphere through the surface, free surface) converges like the smoke
// scene. Before the coarse free surface was placed at each level's spacing and coarse
// couplings took the fine faces inside the coarse cells in series (multigrid_coarsening.h),
// both tanks took 11 iterations at 64^3, against 7 past the sphere. CG and V-cycle reduce in
// fixed chunks, so the count is the same on 1, 2, 3 or 8 workers (checked).
TEST(FluidMultigrid, LiquidTankConvergesLikeTheSmokeScene) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const int liquid = iterationsTo1e6(*tasks, PressureSceneKind::LiquidTank, 64, PressureSolver::CutCellMgpcg);
  const int tank = iterationsTo1e6(*tasks, PressureSceneKind::TankPlateSphere, 64, PressureSolver::CutCellMgpcg);
  std::printf("    64^3: liquid tank %d iterations, plate tank %d\n", liquid, tank);
  EXPECT_LE(liquid, 7);
  EXPECT_LE(tank, 8);
}

// Without boundary smoothing the cut-cell V-cycle loses its resolution independence (sliver
// cells): the sweeps must be doing real work, or the test above is vacuous.
TEST(FluidMultigrid, BoundarySmoothingKeepsIterationCountsDown) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  PressureScene scene;
  makeScene(*tasks, PressureSceneKind::SmokeSphere, 64, &scene);
  int iterations[2];
  for (int withSweeps = 0; withSweeps < 2; ++withSweeps) {
    SceneSolver solver;
    solver.multigrid.boundarySweeps = withSweeps ? MultigridSettings{}.boundarySweeps : 0;
    ASSERT_EQ(solver.prepare(*tasks, scene), Status::Ok);
    std::vector<double> p;
    iterations[withSweeps] = solver.solve(*tasks, scene, 1e-6, 500, &p).iterations;
  }
  std::printf("    64^3 sphere: %d iterations without boundary sweeps, %d with\n", iterations[0], iterations[1]);
  EXPECT_LT(iterations[1], iterations[0]);
}

// Every solver converges to the same pressure (up to the floating region's constant, which the
// filter pins to zero mean for all of them), with the free surface too: the multigrid builds its
// levels from whatever Dirichlet parts the fine operator holds.
TEST(FluidMultigrid, SameSolutionAsMic0Pcg) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  for (PressureSceneKind kind : {PressureSceneKind::SmokeSphere, PressureSceneKind::TankPlateSphere,
                                 PressureSceneKind::ClosedTank, PressureSceneKind::LiquidTank}) {
    PressureScene scene;
    makeScene(*tasks, kind, 32, &scene);
    std::vector<double> reference;
    SceneSolver mic;
    mic.kind = PressureSolver::Mic0Pcg;
    ASSERT_EQ(mic.prepare(*tasks, scene), Status::Ok);
    const CgResult micResult = mic.solve(*tasks, scene, 1e-11, 2000, &reference);
    ASSERT_TRUE(micResult.converged) << testscene::sceneName(kind);
    for (PressureSolver which : {PressureSolver::CutCellMgpcg, PressureSolver::VoxelMgpcg}) {
      SceneSolver solver;
      solver.kind = which;
      ASSERT_EQ(solver.prepare(*tasks, scene), Status::Ok);
      std::vector<double> p;
      const CgResult result = solver.solve(*tasks, scene, 1e-11, 500, &p);
      EXPECT_TRUE(result.converged);
      double diff = 0.0;
      for (size_t c = 0; c < p.size(); ++c) diff += (p[c] - reference[c]) * (p[c] - reference[c]);
      const double relative = std::sqrt(diff / dot(reference, reference));
      std::printf("    %s solver %d: %d iterations (MIC(0) %d), |p - p_mic| / |p_mic| = %.2e\n",
                  testscene::sceneName(kind), static_cast<int>(which), result.iterations, micResult.iterations,
                  relative);
      EXPECT_LT(relative, 1e-7) << testscene::sceneName(kind) << " solver " << static_cast<int>(which);
    }
  }
}

// projectVelocity through each solver: the same projected velocity, the default is the cut-cell
// multigrid, and the multigrid solve is cut by the budget and warm-starts like MIC(0)'s.
TEST(FluidMultigrid, ProjectVelocityGivesTheSameVelocityWithEverySolver) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  EXPECT_EQ(PressureSolveSettings{}.solver, PressureSolver::CutCellMgpcg);
  PressureScene reference;
  makeScene(*tasks, PressureSceneKind::TankPlateSphere, 24, &reference);
  std::vector<double> velocities[3];
  const PressureSolver solvers[3] = {PressureSolver::Mic0Pcg, PressureSolver::VoxelMgpcg, PressureSolver::CutCellMgpcg};
  for (int s = 0; s < 3; ++s) {
    MacGrid grid = reference.grid;
    PressureSolveSettings settings;
    settings.tolerance = 1e-10;
    settings.maxIterations = 1000;
    settings.solver = solvers[s];
    PressureState state;
    PressureSolveStats stats;
    ASSERT_EQ(projectVelocity(*tasks, grid, reference.fractions, 0.01, 1000.0, Deadline(), settings, state, &stats),
              Status::Ok)
        << lastError();
    EXPECT_TRUE(stats.converged) << s;
    for (int a = 0; a < 3; ++a) velocities[s].insert(velocities[s].end(), grid.velocity[a].begin(), grid.velocity[a].end());
  }
  for (int s = 1; s < 3; ++s) {
    double worst = 0.0;
    for (size_t f = 0; f < velocities[0].size(); ++f)
      worst = std::max(worst, std::fabs(velocities[s][f] - velocities[0][f]));
    EXPECT_LT(worst, 1e-7) << "solver " << s;
  }
}

TEST(FluidMultigrid, BudgetCutMultigridSolveConvergesOverFramesByWarmStart) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  PressureScene scene;
  makeScene(*tasks, PressureSceneKind::SmokeSphere, 24, &scene);
  PressureSolveSettings settings;
  settings.tolerance = 1e-10;
  SteppingClock fake;
  PressureState state;
  PressureSolveStats stats;
  int frames = 0;
  for (; frames < 20; ++frames) {
    MacGrid grid = scene.grid;  // the same intermediate velocity every frame
    ASSERT_EQ(projectVelocity(*tasks, grid, scene.fractions, 0.01, 1000.0, Deadline(fake.clock(), 2.0), settings,
                              state, &stats),
              Status::Ok);
    if (stats.converged) break;
    EXPECT_TRUE(stats.budgetCut);
    EXPECT_LE(stats.iterations, 2);
  }
  std::printf("    converged after %d frames of at most 2 iterations\n", frames + 1);
  EXPECT_TRUE(stats.converged);
  EXPECT_GT(frames, 1);
}

}  // namespace
}  // namespace vp

// Free-surface pressure projection (symmetric ghost fluid): hydrostatic rest of a water column
// in a closed tank, with and without a tilted box crossing the surface; divergence-free liquid
// cells after projecting a swirl under a curved surface; the operator's structure.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "collide/face_coverage.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/pressure/pressure_projection.h"
#include "fluid/surface/free_surface.h"
#include "fluid_liquid_test_util.h"

namespace vp {
namespace {

using testutil::forEachFace;

struct Tank {
  MacGrid grid;
  FaceFractionField fractions;
  PreparedCollider collider;
  Array<double> phi;
};

void makeTank(int n, const ColliderShape* shape, Tank* tank) {
  const MacGridSpec spec = testutil::unitCubeGrid(n);
  ASSERT_EQ(initMacGrid(spec, testutil::kClosedTank, &tank->grid), Status::Ok) << lastError();
  ASSERT_EQ(initFaceFractionField(spec, &tank->fractions), Status::Ok) << lastError();
  if (shape != nullptr) {
    ASSERT_EQ(prepareCollider(*shape, &tank->collider), Status::Ok) << lastError();
    const PreparedCollider* list[] = {&tank->collider};
    ASSERT_EQ(computeFaceFractions(list, 1, &tank->fractions), Status::Ok) << lastError();
  }
  tank->phi.assign(static_cast<size_t>(tank->grid.cellCount()), 0.0);
}

template <class Sdf>
void fillPhi(Tank& tank, const Sdf& sdf) {
  tank.phi = testutil::sampleCells(tank.grid, sdf);
}

using testutil::tiltedBox;

Array<double> netOutflow(const Tank& tank) {
  return testutil::netOutflowByDefinition(tank.grid, tank.fractions);
}

// Still water, surface at y = H, gravity added to the velocity before the projection. With phi
// linear (the plane's exact distance) the ghost-fluid theta is the exact crossing, so
// p = rho g (H - y) solves the discrete system exactly: every liquid-liquid face sees the jump
// rho g h, and a liquid-air face p_c / theta = rho g (H - y_c) / ((H - y_c) / h) = rho g h too,
// which cancels the rhs -(rho h / dt)(-g dt) face by face (cut faces included: both sides carry
// the same A_f). So what remains is the CG's residual: with tolerance 1e-10 on |b|_2 the
// pressure error stays far below 1e-6 of the one-cell jump rho g h and the speed below
// 1e-6 g dt (the same margins as the smoke hydrostatic test).
void expectHydrostatic(const ColliderShape* box) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const int n = 20;
  const double surface = 0.6137;  // not on a cell centre or face: theta away from 0 and 1
  Tank tank;
  makeTank(n, box, &tank);
  fillPhi(tank, [&](const Eigen::Vector3d& x) { return x.y() - surface; });
  const double g = 9.81, dt = 0.01, rho = 1000.0, h = tank.grid.spec.h;
  for (double& v : tank.grid.velocity[1]) v -= dt * g;
  const MacGrid before = tank.grid;
  PressureState state;
  PressureSolveStats stats;
  ASSERT_EQ(projectVelocity(*tasks, tank.grid, tank.fractions, dt, rho, Deadline(), PressureSolveSettings{1e-10, 1000},
                            state, &stats, tank.phi.data()),
            Status::Ok)
      << lastError();
  EXPECT_TRUE(stats.converged);
  const CutCellPoisson& op = state.poisson;
  for (uint8_t floating : op.regionFloating) EXPECT_EQ(floating, 0);  // every region touches air
  double maxSpeed = 0.0, worstPressure = 0.0;
  int64_t liquidFaces = 0, airFaces = 0;
  const MacGrid& grid = tank.grid;
  forEachFace(grid, [&](int a, int i, int j, int k, size_t f) {
    Eigen::Vector3i low(i, j, k);
    low[a] -= 1;
    const bool hasLow = low[a] >= 0, hasHigh = Eigen::Vector3i(i, j, k)[a] < n;
    const bool liquid = (hasLow && isLiquid(tank.phi[grid.cellIndex(low.x(), low.y(), low.z())])) ||
                        (hasHigh && isLiquid(tank.phi[grid.cellIndex(i, j, k)]));
    if (liquid) {
      maxSpeed = std::max(maxSpeed, std::fabs(grid.velocity[a][f]));
      ++liquidFaces;
    } else if (!grid.isWallFace(a, i, j, k) && effectiveOpenFraction(grid, tank.fractions, a, i, j, k) > 0.0) {
      // Air-air faces are left to the extrapolation.
      EXPECT_EQ(grid.velocity[a][f], before.velocity[a][f]);
      ++airFaces;
    }
  });
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const size_t c = grid.cellIndex(i, j, k);
        if (!op.isFluid(c)) {
          EXPECT_EQ(state.pressure[c], 0.0);
          continue;
        }
        EXPECT_TRUE(isLiquid(tank.phi[c]));
        const double exact = rho * g * (surface - grid.cellCentre(i, j, k).y());
        worstPressure = std::max(worstPressure, std::fabs(state.pressure[c] - exact));
      }
  std::printf("    liquid cells %lld, iterations %d, residual %.2e, max |u| %.2e over %lld liquid faces, "
              "max pressure error %.2e Pa (rho g h = %.1f Pa)\n",
              static_cast<long long>(op.fluidCellCount), stats.iterations, stats.relativeResidual, maxSpeed,
              static_cast<long long>(liquidFaces), worstPressure, rho * g * h);
  EXPECT_GT(airFaces, 0);
  EXPECT_LT(maxSpeed, 1e-6 * g * dt);
  EXPECT_LT(worstPressure, 1e-6 * rho * g * h);
}

TEST(FluidFreeSurface, HydrostaticWaterColumnInClosedTank) { expectHydrostatic(nullptr); }

TEST(FluidFreeSurface, HydrostaticWithTiltedBoxCrossingTheSurface) {
  // The box spans y in about [0.29, 0.71]: it pierces the surface, so cut faces meet the
  // free surface.
  const ColliderShape box = tiltedBox({0.47, 0.5, 0.52});
  expectHydrostatic(&box);
}

// A swirl under a curved (spherical cap) surface with a box in the liquid: after the
// projection every liquid cell's net outflow is below tol * |netOutflow(u*)|_2 (the bound of
// fluid_projection_test.cpp: netOutflow(u) = (dt / (rho h)) (L p - b) cell by cell, also on
// free-surface cells, since the velocity update uses the ghost gradient the operator used).
TEST(FluidFreeSurface, LiquidCellsDivergenceFreeUnderCurvedSurface) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const ColliderShape box = tiltedBox({0.5, 0.3, 0.5});
  Tank tank;
  makeTank(24, &box, &tank);
  const Eigen::Vector3d centre(0.45, -0.2, 0.55);
  fillPhi(tank, [&](const Eigen::Vector3d& x) { return (x - centre).norm() - 0.85; });
  MacGrid& grid = tank.grid;
  forEachFace(grid, [&](int a, int i, int j, int k, size_t f) {
    const Eigen::Vector3d x = grid.faceCentre(a, i, j, k);
    grid.velocity[a][f] = std::sin(3.0 * x.x() + a) * std::cos(2.0 * x.y() - a) + 0.5 * x.z() * x[a];
  });
  PressureState state;
  ASSERT_EQ(buildCutCellPoisson(*tasks, grid, tank.fractions, &state.poisson, tank.phi.data()), Status::Ok);
  Array<double> initial = netOutflow(tank);
  int64_t liquidCells = 0;
  for (size_t c = 0; c < initial.size(); ++c) {
    if (!state.poisson.isFluid(c)) initial[c] = 0.0;
    else ++liquidCells;
  }
  ASSERT_GT(liquidCells, 1000);
  ASSERT_LT(liquidCells, grid.cellCount() * 3 / 4);  // a real surface, lots of air
  double before = 0.0;
  for (double v : initial) before += v * v;
  before = std::sqrt(before);
  const double tolerance = 1e-8;
  PressureSolveStats stats;
  ASSERT_EQ(projectVelocity(*tasks, grid, tank.fractions, 0.01, 1000.0, Deadline(), PressureSolveSettings{tolerance, 1000},
                            state, &stats, tank.phi.data()),
            Status::Ok);
  EXPECT_TRUE(stats.converged);
  const Array<double> after = netOutflow(tank);
  double worst = 0.0;
  for (size_t c = 0; c < after.size(); ++c)
    if (state.poisson.isFluid(c)) worst = std::max(worst, std::fabs(after[c]));
  std::printf("    liquid cells %lld, iterations %d, max |outflow| %.3g (initial |.|_2 %.3g)\n",
              static_cast<long long>(liquidCells), stats.iterations, worst, before);
  EXPECT_LE(worst, (1.01 * tolerance + 1e-12) * before);
}

// The struct keeps its meaning: couplings only between two liquid cells, diagonal = open
// couplings + A_f / theta on liquid-air faces; air cells have no row.
TEST(FluidFreeSurface, OperatorRowsOfSurfaceCells) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  Tank tank;
  makeTank(6, nullptr, &tank);
  const double surface = 0.41;
  fillPhi(tank, [&](const Eigen::Vector3d& x) { return x.y() - surface; });
  CutCellPoisson op;
  ASSERT_EQ(buildCutCellPoisson(*tasks, tank.grid, tank.fractions, &op, tank.phi.data()), Status::Ok);
  const MacGrid& grid = tank.grid;
  const double h = grid.spec.h;
  // Rows j = 0, 1 are liquid (centres 1/12, 3/12 < 0.41), j = 2 (5/12) is air.
  EXPECT_EQ(op.fluidCellCount, 2 * 36);
  const size_t top = grid.cellIndex(2, 1, 3), air = grid.cellIndex(2, 2, 3), interior = grid.cellIndex(2, 0, 3);
  EXPECT_FALSE(op.isFluid(air));
  EXPECT_EQ(op.diagonal[air], 0.0);
  const double theta = (surface - 1.5 * h) / h;  // top liquid centre at 1.5 h
  EXPECT_NEAR(op.diagonal[top], 4.0 + 1.0 + 1.0 / theta, 1e-12);  // 4 sides, below, surface
  EXPECT_NEAR(op.diagonal[interior], 5.0, 1e-12);                  // the bottom is a wall
  EXPECT_EQ(op.coupling[1][grid.faceIndex(1, 2, 2, 3)], 0.0);      // liquid-air
  EXPECT_EQ(op.coupling[1][grid.faceIndex(1, 2, 1, 3)], 1.0);      // liquid-liquid
  // Without a level set the same grid is one floating smoke region.
  ASSERT_EQ(buildCutCellPoisson(*tasks, tank.grid, tank.fractions, &op), Status::Ok);
  EXPECT_EQ(op.fluidCellCount, 216);
  EXPECT_EQ(op.regionFloating[0], 1);
  // A theta at the clamp: the surface right at a liquid cell's centre.
  EXPECT_EQ(freeSurfaceTheta(-1e-12, 1.0), kMinFreeSurfaceTheta);
  EXPECT_DOUBLE_EQ(freeSurfaceTheta(-0.25, 0.75), 0.25);
}

}  // namespace
}  // namespace vp

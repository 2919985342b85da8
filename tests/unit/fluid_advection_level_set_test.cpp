// A liquid's level set advected through the domain's sides (advection.h, levelSetField): beyond
// an Open side lies air, beyond a Wall the boundary's value (clamped sampling).
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "fluid/advection/advection.h"

namespace vp {
namespace {

constexpr int kN[3] = {5, 6, 4};
constexpr double kH = 0.1;
constexpr double kLiquid = -0.05;  // phi everywhere at the start: the box is full of liquid

// A box full of liquid with a uniform velocity u along y on every y-face; its top is `top`.
MacGrid fallingColumn(double u, DomainSide top) {
  MacGridSpec spec;
  spec.h = kH;
  spec.nx = kN[0], spec.ny = kN[1], spec.nz = kN[2];
  MacGrid g;
  const std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                        top,              DomainSide::Wall, DomainSide::Wall};
  EXPECT_EQ(initMacGrid(spec, sides, &g), Status::Ok);
  std::fill(g.velocity[1].begin(), g.velocity[1].end(), u);
  return g;
}

Array<double> advectedLevelSet(const MacGrid& grid, double dt, AdvectionScheme scheme, int levelSetField) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  Array<double> phi(static_cast<size_t>(grid.cellCount()), kLiquid);
  Array<double>* fields[1] = {&phi};
  AdvectionWorkspace work;
  advectCellScalars(*tasks, grid, dt, scheme, fields, 1, work, nullptr, nullptr, 0.0, -1, levelSetField);
  return phi;
}

// Liquid flowing down from an open top: the top cells' traces end half a cell above the
// domain, in the air, so the top layer turns to air (phi = half a cell) instead of drawing
// liquid from outside; the layers below trace into the liquid and stay as they were.
TEST(FluidAdvectionLevelSet, WhatFlowsInThroughAnOpenSideIsAir) {
  const MacGrid grid = fallingColumn(-1.0, DomainSide::Open);
  const double dt = kH;  // one cell
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack}) {
    const Array<double> phi = advectedLevelSet(grid, dt, scheme, 0);
    for (int k = 0; k < kN[2]; ++k)
      for (int j = 0; j < kN[1]; ++j)
        for (int i = 0; i < kN[0]; ++i) {
          const double value = phi[grid.cellIndex(i, j, k)];
          if (j == kN[1] - 1) EXPECT_NEAR(value, 0.5 * kH, 1e-12) << "top cell " << i << " " << k;
          else EXPECT_EQ(value, kLiquid) << "cell " << i << " " << j << " " << k;
        }
  }
}

// The same flow as a plain scalar, or with the top a Wall: clamped sampling, nothing changes.
TEST(FluidAdvectionLevelSet, PlainScalarsAndWallSidesKeepClampedSampling) {
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack}) {
    for (const Array<double>& phi : {advectedLevelSet(fallingColumn(-1.0, DomainSide::Open), kH, scheme, -1),
                                     advectedLevelSet(fallingColumn(-1.0, DomainSide::Wall), kH, scheme, 0)})
      for (double value : phi) EXPECT_EQ(value, kLiquid);
  }
}

// Flowing out through the open top, every trace stays inside: the rule changes nothing.
TEST(FluidAdvectionLevelSet, OutflowIsUnchanged) {
  const MacGrid grid = fallingColumn(1.0, DomainSide::Open);
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack}) {
    const Array<double> with = advectedLevelSet(grid, kH, scheme, 0), without = advectedLevelSet(grid, kH, scheme, -1);
    EXPECT_EQ(with, without);
  }
}

}  // namespace
}  // namespace vp

// A conserved scalar (advection.h, advectCellScalars' conservedField): its total after
// advection is the old total less what the open sides' outward velocities carried out.
#include <gtest/gtest.h>

#include <array>
#include <numeric>
#include <vector>

#include "fluid/advection/advection.h"

namespace vp {
namespace {

constexpr int kN[3] = {6, 8, 5};

// A box with an open top and a uniform upward velocity u on every y-face.
MacGrid risingGrid(double u) {
  MacGridSpec spec;
  spec.h = 0.1;
  spec.nx = kN[0], spec.ny = kN[1], spec.nz = kN[2];
  MacGrid g;
  const std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                        DomainSide::Open, DomainSide::Wall, DomainSide::Wall};
  EXPECT_EQ(initMacGrid(spec, sides, &g), Status::Ok);
  std::fill(g.velocity[1].begin(), g.velocity[1].end(), u);
  return g;
}

double total(const Array<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

TEST(FluidAdvectionConservation, WhatLeavesThroughAnOpenSideIsTakenFromTheTotal) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const MacGrid grid = risingGrid(1.0);
  const double dt = 0.5 * grid.spec.h;  // half a cell: half of the top row leaves
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack}) {
    Array<double> smoke(static_cast<size_t>(grid.cellCount()), 1.0), plain = smoke;
    Array<double>* conserved[1] = {&smoke};
    Array<double>* unconserved[1] = {&plain};
    AdvectionWorkspace work;
    advectCellScalars(*tasks, grid, dt, scheme, unconserved, 1, work);
    // Clamped sampling keeps a uniform field uniform: without the correction nothing leaves.
    EXPECT_DOUBLE_EQ(total(plain), grid.cellCount());
    advectCellScalars(*tasks, grid, dt, scheme, conserved, 1, work, nullptr, nullptr, 0.0, 0);
    EXPECT_NEAR(total(smoke), grid.cellCount() - 0.5 * kN[0] * kN[2], 1e-9);
  }
}

TEST(FluidAdvectionConservation, InflowBringsNothingAndWallsLetNothingOut) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  const MacGrid down = risingGrid(-1.0);  // air flows in through the open top
  Array<double> smoke(static_cast<size_t>(down.cellCount()));
  for (size_t c = 0; c < smoke.size(); ++c) smoke[c] = 0.5 + 0.01 * static_cast<double>(c % 7);
  const double before = total(smoke);
  Array<double>* fields[1] = {&smoke};
  AdvectionWorkspace work;
  advectCellScalars(*tasks, down, 0.5 * down.spec.h, AdvectionScheme::MacCormack, fields, 1, work, nullptr, nullptr,
                    0.0, 0);
  EXPECT_NEAR(total(smoke), before, 1e-9 * before);
}

}  // namespace
}  // namespace vp

// The fluid's energy account for the divergence guard (fluid/fluid_step_energy.h): the kinetic
// energy over the fluid's open faces, and the source bound, which is reached exactly when the
// whole mass is accelerated along its flow (the triangle inequality's equality case).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/task_system.h"
#include "fluid/fluid_step_energy.h"

namespace vp {
namespace {

struct Box {
  MacGrid grid;
  FaceFractionField fractions;
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  explicit Box(int n) {
    MacGridSpec spec;
    spec.nx = spec.ny = spec.nz = n;
    spec.h = 0.25;
    EXPECT_EQ(initMacGrid(spec, {}, &grid), Status::Ok);
    EXPECT_EQ(initFaceFractionField(spec, &fractions), Status::Ok);
  }
};

TEST(FluidStepEnergy, AUniformFlowOverItsOpenFaces) {
  Box box(4);
  const double u0 = 3.0, rho = 2.0, h = box.grid.spec.h;
  std::fill(box.grid.velocity[0].begin(), box.grid.velocity[0].end(), u0);
  const double faces = 5.0 * 4.0 * 4.0;  // x faces of a 4^3 grid
  const double whole = 0.5 * rho * h * h * h * faces * u0 * u0;
  EXPECT_NEAR(fluidKineticEnergy(*box.tasks, box.grid, box.fractions, nullptr, rho), whole, 1e-12 * whole);
  // Half of every x face inside a solid: half the fluid moves.
  std::fill(box.fractions.open[0].begin(), box.fractions.open[0].end(), 0.5);
  EXPECT_NEAR(fluidKineticEnergy(*box.tasks, box.grid, box.fractions, nullptr, rho), 0.5 * whole, 1e-12 * whole);
}

TEST(FluidStepEnergy, ALiquidCountsTheFacesBesideItsCells) {
  Box box(4);
  const double u0 = 1.0, rho = 1000.0, h = box.grid.spec.h;
  for (int a = 0; a < 3; ++a) std::fill(box.grid.velocity[a].begin(), box.grid.velocity[a].end(), u0);
  Array<double> phi(static_cast<size_t>(box.grid.cellCount()), 1.0);
  phi[box.grid.cellIndex(1, 2, 3)] = -0.1;  // one liquid cell: its six faces
  const double one = 0.5 * rho * h * h * h * u0 * u0;
  EXPECT_NEAR(fluidKineticEnergy(*box.tasks, box.grid, box.fractions, phi.data(), rho), 6.0 * one, 1e-9);
  phi[box.grid.cellIndex(2, 2, 3)] = -0.1;  // a neighbour along x: they share one face
  EXPECT_NEAR(fluidKineticEnergy(*box.tasks, box.grid, box.fractions, phi.data(), rho), 11.0 * one, 1e-9);
}

TEST(FluidStepEnergy, TheSourceBoundIsReachedByTheWholeMassAcceleratedAlongItsFlow) {
  const double mass = 8.0, v = 2.0, a = 9.81, dt = 0.1, solid = 0.5;
  const double start = 0.5 * mass * v * v;
  const double end = 0.5 * mass * (v + a * dt + solid) * (v + a * dt + solid);
  EXPECT_NEAR(fluidSourceWorkBound(start, mass, a, solid, dt), end - start, 1e-12 * end);
  EXPECT_NEAR(fluidSourceWorkBound(0.0, mass, a, 0.0, dt), 0.5 * mass * a * dt * a * dt, 1e-12);
  EXPECT_EQ(fluidSourceWorkBound(start, mass, 0.0, 0.0, dt), 0.0);  // no source: no energy
}

TEST(FluidStepEnergy, SmokeAccelerationFromItsBuoyancyAndConfinement) {
  SmokeParameters smoke;
  smoke.densityBuoyancy = 0.5;
  smoke.thermalBuoyancy = 2.0;
  smoke.vorticityConfinement = 0.1;
  EXPECT_DOUBLE_EQ(smokeAccelerationBound(smoke, 9.81, 3.0, 4.0, 0.0), 0.5 * 3.0 + 2.0 * 4.0);
  EXPECT_DOUBLE_EQ(smokeAccelerationBound(smoke, 0.0, 3.0, 4.0, 0.0), 0.0);  // no buoyancy without gravity
  EXPECT_DOUBLE_EQ(smokeAccelerationBound(smoke, 0.0, 0.0, 0.0, 5.0), 4.0 * std::sqrt(3.0) * 0.1 * 5.0);
}

}  // namespace
}  // namespace vp

// Implicit viscosity (fluid/viscosity.h): a shear wave decays at the backward-Euler rate of the
// discrete Laplacian and, within the discretization error, at the analytic exp(-nu k^2 t);
// nu = 0 touches nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "fluid/fluid_actor.h"
#include "fluid/viscosity.h"

namespace vp {
namespace {

// A slab 1 m high between no-slip walls at y = 0 and y = 1, open (zero-gradient) along x and
// z, so u_x(y) = sin(m pi y) with nothing else is a shear wave: divergence-free, and
// uniform along x and z where the open sides add no term.
struct ShearSlab {
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  MacGrid grid;
  FaceFractionField fractions;
  ViscosityWorkspace work;

  explicit ShearSlab(int ny) {
    MacGridSpec spec;
    spec.h = 1.0 / ny;
    spec.nx = 4, spec.ny = ny, spec.nz = 3;
    const std::array<DomainSide, 6> sides{DomainSide::Open, DomainSide::Open, DomainSide::Wall,
                                          DomainSide::Wall, DomainSide::Open, DomainSide::Open};
    EXPECT_EQ(initMacGrid(spec, sides, &grid), Status::Ok);
    EXPECT_EQ(initFaceFractionField(spec, &fractions), Status::Ok);
  }
  double y(int j) const { return (j + 0.5) * grid.spec.h; }
  void setWave(int mode) {
    const Eigen::Vector3i d = grid.faceDims(0);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) grid.velocity[0][grid.faceIndex(0, i, j, k)] = std::sin(mode * M_PI * y(j));
  }
  // Largest |u_x - amplitude sin(m pi y)| over all u-faces, and of |v|, |w|.
  double errorFrom(int mode, double amplitude) const {
    double worst = 0.0;
    const Eigen::Vector3i d = grid.faceDims(0);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i)
          worst = std::max(worst, std::abs(grid.velocity[0][grid.faceIndex(0, i, j, k)] -
                                           amplitude * std::sin(mode * M_PI * y(j))));
    for (int a = 1; a < 3; ++a)
      for (double v : grid.velocity[a]) worst = std::max(worst, std::abs(v));
    return worst;
  }
  ViscosityStats step(double nu, double dt, const ViscositySettings& settings) {
    ViscosityStats stats;
    EXPECT_EQ(applyViscosity(*tasks, grid, fractions, nullptr, nu, dt, Deadline{}, settings, work, &stats),
              Status::Ok)
        << lastError();
    return stats;
  }
};

// With the walls midway between the first and the ghost u-face (reflected ghost), sin(k y),
// k = m pi, is an exact eigenvector of the discrete Laplacian, eigenvalue
// -(4 / h^2) sin^2(k h / 2); each backward-Euler step divides it by 1 + dt nu (4 / h^2)
// sin^2(k h / 2). At nu dt / h^2 = 4.3, 26 times the explicit limit 1/6.
TEST(FluidViscosity, ShearWaveDecaysAtTheDiscreteBackwardEulerRate) {
  ShearSlab slab(16);
  const int mode = 3, steps = 10;
  const double nu = 1.0, dt = 1.0 / 60.0, h = slab.grid.spec.h;
  slab.setWave(mode);
  ViscositySettings tight;
  tight.tolerance = 1e-12;
  const double perStep = 1.0 / (1.0 + dt * nu * 4.0 / (h * h) * std::pow(std::sin(mode * M_PI * h / 2), 2));
  int iterations = 0;
  for (int s = 0; s < steps; ++s) {
    const ViscosityStats stats = slab.step(nu, dt, tight);
    EXPECT_TRUE(stats.solve.converged);
    iterations = std::max(iterations, stats.solve.iterations);
  }
  const double amplitude = std::pow(perStep, steps);
  std::printf("shear wave m=%d: amplitude %.6g after %d steps at nu dt/h^2 = %.2f, <= %d CG iterations a step\n",
              mode, amplitude, steps, nu * dt / (h * h), iterations);
  EXPECT_LT(slab.errorFrom(mode, amplitude), 1e-9);
}

// Against the continuum, exp(-nu k^2 t): backward Euler is first order in time, each step's
// factor 1 / (1 + z) (z = nu k^2 dt) differs from exp(-z) by z^2 / 2, so after N steps the
// amplitude is off by about N z^2 / 2 = 8e-5; the discrete eigenvalue is k^2 (1 - (k h)^2 / 12),
// off by nu k^2 t (k h)^2 / 12 = 3e-4 of the amplitude. 1e-3 covers both with margin and
// still fails if the no-slip walls sat half a cell off (at the ghost face: a decay rate off
// by 11%, 1e-2 of the amplitude).
TEST(FluidViscosity, ShearWaveDecaysAsTheAnalyticSolution) {
  ShearSlab slab(16);
  const int mode = 1, steps = 60;
  const double nu = 0.01, dt = 1.0 / 60.0, k = mode * M_PI;
  slab.setWave(mode);
  for (int s = 0; s < steps; ++s) slab.step(nu, dt, ViscositySettings{});
  const double analytic = std::exp(-nu * k * k * steps * dt);
  const double error = slab.errorFrom(mode, analytic);
  std::printf("shear wave m=1 after 1 s: analytic amplitude %.5f, largest difference %.2e\n", analytic, error);
  EXPECT_LT(error, 1e-3);
}

TEST(FluidViscosity, ZeroViscosityLeavesTheVelocityBitForBit) {
  ShearSlab slab(8);
  for (int a = 0; a < 3; ++a)
    for (size_t f = 0; f < slab.grid.velocity[a].size(); ++f) slab.grid.velocity[a][f] = std::sin(0.37 * f + a);
  const MacGrid before = slab.grid;
  const ViscosityStats stats = slab.step(0.0, 1.0 / 60.0, ViscositySettings{});
  EXPECT_EQ(stats.unknowns, 0);
  EXPECT_EQ(stats.solve.iterations, 0);
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(std::memcmp(before.velocity[a].data(), slab.grid.velocity[a].data(),
                          before.velocity[a].size() * sizeof(double)),
              0);
}

TEST(FluidViscosity, InvalidArgumentsAreRejectedAndChangeNothing) {
  ShearSlab slab(8);
  slab.setWave(1);
  const MacGrid before = slab.grid;
  ViscosityStats stats;
  for (double nu : {-1.0, std::nan(""), double(INFINITY)})
    EXPECT_EQ(applyViscosity(*slab.tasks, slab.grid, slab.fractions, nullptr, nu, 0.01, Deadline{},
                             ViscositySettings{}, slab.work, &stats),
              Status::InvalidArgument);
  EXPECT_EQ(applyViscosity(*slab.tasks, slab.grid, slab.fractions, nullptr, 0.1, 0.0, Deadline{},
                           ViscositySettings{}, slab.work, &stats),
            Status::InvalidArgument);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(before.velocity[a], slab.grid.velocity[a]);
}

// The inviscid actor does not enter the viscosity phase at all: no time, no iterations.
TEST(FluidViscosity, InviscidActorSkipsThePhase) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  FluidDesc d;
  d.kind = FluidKind::Liquid;
  d.grid.h = 1.0 / 8;
  d.grid.nx = d.grid.ny = d.grid.nz = 8;
  FluidShape water;
  water.centre = Vec3(0.25, 0.5, 0.5);
  water.halfExtents = Vec3(0.25, 0.5, 0.5);
  d.initialLiquid.push_back(water);
  for (double nu : {0.0, 0.05}) {
    d.kinematicViscosity = nu;
    std::unique_ptr<FluidActor> actor;
    ASSERT_EQ(FluidActor::create(d, *tasks, &actor), Status::Ok) << lastError();
    FluidStepInput input;
    input.gravity = Vec3(0, -9.81, 0);
    input.tasks = tasks.get();
    ActorStats stats;
    for (int s = 0; s < 3; ++s) actor->step(input, &stats, nullptr);
    const PhaseStats& phase = stats.phase(Phase::Viscosity);
    if (nu == 0.0) {
      EXPECT_EQ(phase.ms, 0.0);
      EXPECT_EQ(phase.iterations, 0);
    } else {
      EXPECT_GT(phase.iterations, 0);
      EXPECT_LT(phase.residual, 1e-4);
    }
  }
}

}  // namespace
}  // namespace vp

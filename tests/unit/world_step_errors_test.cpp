// A phase that fails inside a step is reported, not swallowed: World::step returns
// PhaseFailed naming the actor and the phase, the frame's stats flag it, the rest of the step
// completes, and the next step is clean. Failures are injected (FluidActor's test hook) since
// the solvers do not fail on valid input.
#include <gtest/gtest.h>

#include <ostream>

#include <string>

#include "world.h"

namespace vp {
namespace {

struct Case {
  FluidKind kind;
  double viscosity;
  Phase phase;
};

// Names the case by value (gtest prints an unnamed struct's bytes, padding included, which
// differ from run to run).
void PrintTo(const Case& c, std::ostream* out) {
  *out << (c.kind == FluidKind::Smoke ? "smoke" : "liquid") << "_phase" << static_cast<int>(c.phase)
       << (c.viscosity > 0.0 ? "_viscous" : "");
}

class StepErrors : public testing::TestWithParam<Case> {};

// An unbudgeted world with one 8^3 fluid (a liquid half full), stepped once: past the first
// step's setup.
void worldWithFluid(FluidKind kind, double viscosity, std::unique_ptr<World>* world, FluidHandle* h) {
  WorldConfig config;
  config.frameBudgetMs = 0.0;
  ASSERT_EQ(World::create(config, world), Status::Ok);
  FluidDesc desc;
  desc.kind = kind;
  desc.name = "tank";
  desc.grid.nx = desc.grid.ny = desc.grid.nz = 8;
  desc.grid.h = 0.125;
  desc.kinematicViscosity = viscosity;
  if (kind == FluidKind::Liquid) {
    FluidShape water;
    water.type = FluidShape::Type::Box;
    water.centre = Vec3(0.5, 0.25, 0.5);
    water.halfExtents = Vec3(0.5, 0.25, 0.5);
    desc.initialLiquid.push_back(water);
  }
  ASSERT_EQ((*world)->createFluid(std::move(desc), h), Status::Ok) << lastError();
  ASSERT_EQ((*world)->step(1.0 / 60.0), Status::Ok) << lastError();
}

TEST_P(StepErrors, AFailedFluidPhaseIsReportedAndTheWorldStepsOn) {
  const Case c = GetParam();
  std::unique_ptr<World> world;
  FluidHandle h;
  ASSERT_NO_FATAL_FAILURE(worldWithFluid(c.kind, c.viscosity, &world, &h));
  world->fluid(h)->injectPhaseFailureForTesting(c.phase);
  ASSERT_EQ(world->step(1.0 / 60.0), Status::PhaseFailed);
  const std::string expected = "fluid (" + std::to_string(h.index1) + ", " + std::to_string(h.generation) +
                               "): phase " + std::to_string(static_cast<int>(c.phase)) + " failed";
  EXPECT_NE(std::string(lastError()).find(expected), std::string::npos) << lastError();
  const ActorStats* fluid = nullptr;
  for (const ActorStats& a : world->lastStats().actors)
    if (a.kind == ActorKind::Fluid) fluid = &a;
  ASSERT_NE(fluid, nullptr);
  EXPECT_TRUE(fluid->phase(c.phase).failed);
  EXPECT_TRUE(fluid->completedStep);  // the rest of the step ran
  EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok) << lastError();
  for (const ActorStats& a : world->lastStats().actors)
    for (const PhaseStats& p : a.phases) EXPECT_FALSE(p.failed);
}

// The liquid's surface is extracted on request, outside a step: a failure there is the
// request's error (named), not a log line behind an empty mesh; the next request succeeds.
TEST(ReadErrors, AFailedSurfaceExtractionIsTheRequestsErrorAndIsRetried) {
  std::unique_ptr<World> world;
  FluidHandle h;
  ASSERT_NO_FATAL_FAILURE(worldWithFluid(FluidKind::Liquid, 0.0, &world, &h));
  FluidActor& tank = *world->fluid(h);
  tank.injectPhaseFailureForTesting(Phase::Surface);
  const FluidSurface* surface = nullptr;
  EXPECT_EQ(tank.surface(&surface), Status::Internal);
  EXPECT_NE(std::string(lastError()).find("fluid 'tank': surface extraction"), std::string::npos) << lastError();
  EXPECT_TRUE(surface->triangles.empty());
  ASSERT_EQ(tank.surface(&surface), Status::Ok) << lastError();
  EXPECT_GT(surface->triangles.size(), 10u);
}

INSTANTIATE_TEST_SUITE_P(EachFallibleFluidPhase, StepErrors,
                         testing::Values(Case{FluidKind::Smoke, 0.0, Phase::Fractions},
                                         Case{FluidKind::Smoke, 0.0, Phase::Pressure},
                                         Case{FluidKind::Smoke, 1e-3, Phase::Viscosity},
                                         Case{FluidKind::Liquid, 0.0, Phase::Pressure},
                                         Case{FluidKind::Liquid, 0.0, Phase::Surface},
                                         Case{FluidKind::Liquid, 0.0, Phase::Advect}));

}  // namespace
}  // namespace vp

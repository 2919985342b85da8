// Fluid pacing under the frame budget (fluid_pacing.h): the interval the policy picks from
// measured costs, the staggered schedule, and the world keeping every fluid's time when it
// defers steps (deterministic: an injected clock that ticks per reading).
#include <gtest/gtest.h>

#include "fluid_pacing.h"
#include "geometry/box_tet_mesh.h"
#include "world.h"

namespace vp {
namespace {

// Feeds the same frame costs `frames` times: fluidCount fluids of fluidStepMs each.
void observeFrames(FluidPacing& pacing, int frames, double budgetMs, double otherMs, double fluidStepMs,
                   int fluidCount) {
  for (int f = 0; f < frames; ++f) pacing.observe(budgetMs, otherMs, fluidCount * fluidStepMs);
}

TEST(FluidPacing, StepsEveryFrameWhenTheFluidsFitOrTheBudgetIsUnlimited) {
  FluidPacing fits;
  observeFrames(fits, 10, 16.0, 5.0, 4.0, 2);  // 5 + 2 * 4 = 13 ms: fits in 0.85 of the room
  EXPECT_EQ(fits.interval(), 1);
  FluidPacing unlimited;
  observeFrames(unlimited, 10, 0.0, 5.0, 400.0, 2);
  EXPECT_EQ(unlimited.interval(), 1);
}

TEST(FluidPacing, PicksTheSmallestIntervalThatFitsAndCapsIt) {
  // Two fluids of 8 ms, 5 ms of other work, 16 ms budget: room 11 ms, 0.85 of it 9.35 ms;
  // 16 ms of fluid per frame does not fit, 8 ms (every other frame) does.
  FluidPacing two;
  observeFrames(two, 1, 16.0, 5.0, 8.0, 2);
  EXPECT_EQ(two.interval(), 2);
  // 2 * 14 ms: 28 / 3 = 9.33 ms fits, 14 does not.
  FluidPacing three;
  observeFrames(three, 1, 16.0, 5.0, 14.0, 2);
  EXPECT_EQ(three.interval(), 3);
  FluidPacing capped;
  observeFrames(capped, 1, 16.0, 15.0, 50.0, 2);
  EXPECT_EQ(capped.interval(), FluidPacing::kMaxInterval);
}

TEST(FluidPacing, RaisesAtOnceAndLowersOnlyAfterCalmFrames) {
  FluidPacing pacing;
  observeFrames(pacing, 1, 16.0, 5.0, 8.0, 2);
  ASSERT_EQ(pacing.interval(), 2);
  // Costs fall to 3 ms a step: 6 ms every frame fits in 0.7 * 11 = 7.7 ms, and after
  // kCalmFrames such frames the interval comes down.
  int lowered = -1;
  for (int f = 0; f < 200 && lowered < 0; ++f) {
    observeFrames(pacing, 1, 16.0, 5.0, 3.0, 2);
    if (pacing.interval() == 1) lowered = f;
  }
  EXPECT_EQ(lowered, FluidPacing::kCalmFrames - 1);
  // A frame whose fluids cost more than fits raises it on that frame.
  FluidPacing spike;
  observeFrames(spike, 50, 16.0, 5.0, 3.0, 2);
  ASSERT_EQ(spike.interval(), 1);
  observeFrames(spike, 1, 16.0, 5.0, 12.0, 2);
  EXPECT_EQ(spike.interval(), 3);  // 24 ms of fluids: 24 / 3 = 8 <= 0.85 * 11
}

TEST(FluidPacing, StaggersFluidsSoEachFrameCarriesItsShare) {
  FluidPacing pacing;
  observeFrames(pacing, 1, 16.0, 5.0, 8.0, 2);
  ASSERT_EQ(pacing.interval(), 2);
  for (uint64_t frame = 1; frame <= 12; ++frame) {
    const int steps = int(pacing.due(frame, 0, 2, 0)) + int(pacing.due(frame, 1, 2, 0));
    EXPECT_EQ(steps, 1) << "frame " << frame;
  }
  // Two fluids at interval 4: two frames apart, each once in four frames.
  FluidPacing four;
  observeFrames(four, 1, 16.0, 15.0, 50.0, 2);
  ASSERT_EQ(four.interval(), 4);
  for (uint64_t frame = 0; frame < 8; ++frame) {
    EXPECT_EQ(four.due(frame, 0, 2, 0), frame % 4 == 0) << frame;
    EXPECT_EQ(four.due(frame, 1, 2, 0), frame % 4 == 2) << frame;
  }
  // However the interval moves, nothing waits kMaxInterval frames.
  EXPECT_TRUE(pacing.due(3, 0, 2, FluidPacing::kMaxInterval - 1));
}

// Every reading of the clock advances it by one tick, so the cost of a fluid step is a fixed
// number of ticks.
struct TickClock {
  double seconds = 0.0;
  double tick = 1e-4;
  static double read(void* self) {
    auto* c = static_cast<TickClock*>(self);
    c->seconds += c->tick;
    return c->seconds;
  }
};

// still: no emitter velocity and no buoyancy, so nothing ever moves.
FluidDesc smallSmoke(double x, bool still) {
  FluidDesc d;
  d.kind = FluidKind::Smoke;
  d.grid.origin = Vec3(x, 0, 0);
  d.grid.h = 0.1;
  d.grid.nx = d.grid.ny = d.grid.nz = 8;
  FluidEmitter e;
  e.shape.type = FluidShape::Type::Sphere;
  e.shape.centre = Vec3(x + 0.4, 0.2, 0.4);
  e.shape.radius = 0.15;
  e.velocity = still ? Vec3::Zero() : Vec3(0, 0.5, 0);
  e.densityRate = 1.0;
  e.temperature = 1.0;
  d.emitters.push_back(e);
  if (still) d.smoke.thermalBuoyancy = d.smoke.densityBuoyancy = d.smoke.vorticityConfinement = 0.0;
  return d;
}

struct PacedWorld {
  TickClock clock;
  std::unique_ptr<World> world;
  explicit PacedWorld(double budgetMs, bool still = false) {
    WorldConfig config;
    config.frameBudgetMs = budgetMs;
    config.clock = Clock{&TickClock::read, &clock};
    EXPECT_EQ(World::create(config, &world), Status::Ok);
    for (int f = 0; f < 2; ++f) {
      FluidHandle h;
      EXPECT_EQ(world->createFluid(smallSmoke(2.0 * f, still), &h), Status::Ok);
    }
  }
};

TEST(FluidPacing, TheWorldDefersFluidsUnderATightBudgetAndKeepsTheirTime) {
  const double dt = 1.0 / 60.0;
  PacedWorld tight(0.5);  // far less than a fluid step costs in ticks
  std::vector<double> simulated(2, 0.0);
  int deferredSteps = 0;
  const int frames = 40;
  for (int f = 0; f < frames; ++f) {
    ASSERT_EQ(tight.world->step(dt), Status::Ok);
    const StepStats& s = tight.world->lastStats();
    ASSERT_EQ(s.actors.size(), 3u);  // rigid, then both fluids, stepped or not
    for (int k = 0; k < 2; ++k) {
      const ActorStats& a = s.actors[1 + k];
      EXPECT_EQ(a.kind, ActorKind::Fluid);
      simulated[k] += a.simulatedDt;
      if (a.simulatedDt == 0.0) {
        ++deferredSteps;
        EXPECT_EQ(a.totalMs, 0.0);
      }
      // Never more than the interval's worth of frames at once.
      EXPECT_LE(a.simulatedDt, FluidPacing::kMaxInterval * dt + 1e-12);
    }
  }
  EXPECT_EQ(tight.world->lastStats().fluidInterval, FluidPacing::kMaxInterval);
  EXPECT_GT(deferredSteps, frames);  // most fluid steps were deferred
  // Each fluid has simulated all the time but what it still holds (less than an interval).
  for (int k = 0; k < 2; ++k) {
    EXPECT_LE(simulated[k], frames * dt + 1e-9);
    EXPECT_GT(simulated[k], (frames - FluidPacing::kMaxInterval) * dt - 1e-9);
  }

  PacedWorld unlimited(0.0);
  for (int f = 0; f < 10; ++f) {
    ASSERT_EQ(unlimited.world->step(dt), Status::Ok);
    const StepStats& s = unlimited.world->lastStats();
    EXPECT_EQ(s.fluidInterval, 1);
    for (int k = 0; k < 2; ++k) EXPECT_EQ(s.actors[1 + k].simulatedDt, dt);
  }
}

TEST(FluidPacing, ADeferredFluidEmitsForAllTheTimeItSimulates) {
  // A still emitter in still air (no velocity, no buoyancy): nothing moves, so the smoke in the
  // box is the emission rate times the simulated time, however the time was cut into steps.
  const double dt = 1.0 / 60.0;
  PacedWorld tight(0.5, true), unlimited(0.0, true);
  std::vector<double> simulated(2, 0.0);
  const int frames = 48;
  for (int f = 0; f < frames; ++f) {
    ASSERT_EQ(tight.world->step(dt), Status::Ok);
    ASSERT_EQ(unlimited.world->step(dt), Status::Ok);
    for (int k = 0; k < 2; ++k) simulated[k] += tight.world->lastStats().actors[1 + k].simulatedDt;
  }
  const std::vector<FluidHandle> paced = tight.world->fluidHandles(), everyFrame = unlimited.world->fluidHandles();
  for (int k = 0; k < 2; ++k) {
    const double reference = unlimited.world->fluid(everyFrame[k])->totalSmoke();
    ASSERT_GT(reference, 0.0);
    ASSERT_LT(simulated[k], frames * dt);  // some time is still pending: the check is not trivial
    EXPECT_NEAR(tight.world->fluid(paced[k])->totalSmoke(), reference * simulated[k] / (frames * dt), 1e-12 * reference);
  }
}

TEST(FluidPacing, TheDeformablesLeaveTheDueFluidsTheirExpectedTime) {
  // One smoke fluid and one pinned bar whose solve never converges (it always takes all the
  // time it is given, ~210 iterations to converge). The budget holds the fluid every frame
  // (interval 1); from the second
  // frame on the bar's share ends the fluid's smoothed cost before the frame's end.
  const double dt = 1.0 / 60.0, budgetMs = 10.0;
  TickClock clock;
  WorldConfig config;
  config.frameBudgetMs = budgetMs;
  config.clock = Clock{&TickClock::read, &clock};
  std::unique_ptr<World> world;
  ASSERT_EQ(World::create(config, &world), Status::Ok);
  DeformableDesc bar;
  bar.mesh = makeBoxTetMesh({12, 3, 3}, Vec3(3, 0.5, 0.5), Vec3::Zero());
  bar.material.youngsModulus = 1e7;
  bar.solver.tolerance = 1e-12;
  bar.solver.maxIterations = 100000;
  bar.solver.preconditioner = Preconditioner::BlockJacobi;
  DeformableHandle barHandle;
  ASSERT_EQ(world->createDeformable(std::move(bar), &barHandle), Status::Ok);
  DeformableBody& body = *world->deformable(barHandle);
  std::vector<int32_t> left;  // a pinned end makes the bar sag: the solve has work to do
  for (int32_t i = 0; i < body.nodeCount(); ++i)
    if (body.restPositions()[3 * i] == 0.0) left.push_back(i);
  body.setPinned(left.data(), static_cast<int64_t>(left.size()), true);
  FluidHandle fluid;
  ASSERT_EQ(world->createFluid(smallSmoke(0.0, false), &fluid), Status::Ok);
  double expected = -1.0;  // the policy's smoothing of the fluid's measured cost, replayed
  for (int f = 0; f < 6; ++f) {
    ASSERT_EQ(world->step(dt), Status::Ok);
    const StepStats& s = world->lastStats();
    ASSERT_EQ(s.fluidInterval, 1);
    const ActorStats& deformable = s.actors[1];
    const ActorStats& smoke = s.actors[2];
    ASSERT_GT(smoke.simulatedDt, 0.0);
    EXPECT_TRUE(deformable.phase(Phase::Solve).budgetCut);
    // The bar runs until its share ends, plus one iteration's few clock readings (a smoke step
    // here reads the clock 10 times: 1 ms).
    constexpr double kOneIterationMs = 0.35;
    const double reserve = FluidPacing::kReserveMargin * std::max(expected, 0.0);
    EXPECT_NEAR(deformable.totalMs, budgetMs - reserve, kOneIterationMs) << "frame " << f;
    expected = FluidPacing::smoothed(expected, smoke.totalMs);
  }
  EXPECT_GT(expected, 0.9);  // the reserve is several times the tolerance above
}

}  // namespace
}  // namespace vp

// The frame plan (frame_plan.h) with an injected tick clock, so budget behaviour is
// deterministic: the policy's parts on their own, then worlds under budgets of 4 to 33 ms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <limits>

#include "frame_plan.h"
#include "geometry/box_tet_mesh.h"
#include "scene/scene_loader.h"
#include "tick_clock.h"
#include "world.h"

namespace vp {
namespace {

TEST(FramePlan, ServesHigherPrioritiesFirstAndEqualOnesInSlotOrder) {
  EXPECT_EQ(FramePlan::byPriority({0, 5, 0, -1, 5}), (std::vector<int>{1, 4, 0, 2, 3}));
}

TEST(FramePlan, StaggersDeformablesOverTheirInterval) {
  ActorSchedule s;
  s.interval = 4;
  const FramePlan::Deformable d{0, &s};
  // Two deformables at interval 4 step on frames 0 and 2 mod 4 (ordinal 0 and 1 of 2).
  for (uint64_t frame = 0; frame < 4; ++frame) {
    EXPECT_EQ(FramePlan::due(frame, 0, 2, d), frame % 4 == 0) << frame;
    EXPECT_EQ(FramePlan::due(frame, 1, 2, d), frame % 4 == 2) << frame;
  }
  s.waitedFrames = 3;  // it has waited its interval out: due whatever the frame
  EXPECT_TRUE(FramePlan::due(1, 0, 2, d));
}

TEST(FramePlan, ADeformablePacedByLiquidsStepsWhenOneOfThemCompletedAStep) {
  ActorSchedule s;
  s.interval = 4;
  s.liquidSteps = 7;  // the liquids' completed steps when it last stepped
  FramePlan::Deformable d{0, &s, FramePlan::Pacing::WithLiquids, 7};
  for (uint64_t frame = 0; frame < 8; ++frame) EXPECT_FALSE(FramePlan::due(frame, 0, 1, d)) << frame;
  d.liquidSteps = 8;
  EXPECT_TRUE(FramePlan::due(1, 0, 1, d));  // whatever its interval and the frame
  d.liquidSteps = 7;
  s.waitedFrames = FramePlan::kMaxInterval - 1;  // no liquid step since kMaxInterval frames
  EXPECT_TRUE(FramePlan::due(1, 0, 1, d));
  const FramePlan::Deformable nearBall{0, &s, FramePlan::Pacing::EveryFrame};
  s.waitedFrames = 0;
  for (uint64_t frame = 0; frame < 8; ++frame) EXPECT_TRUE(FramePlan::due(frame, 0, 1, nearBall)) << frame;
  // A step that blew up at the liquid's interval: its own rate (every frame) for a while.
  FramePlan::noteDiverged(s);
  EXPECT_EQ(s.interval, 1);
  EXPECT_EQ(s.ownRateFrames, FramePlan::kCalmFrames);
}

TEST(FramePlan, AFluidStepMustGoItsShareOfTheWayEachFrameAtTheCap) {
  ActorSchedule s;
  FramePlan::Fluid f{0, &s, 80000, 0};
  // Paced to end a frame before the cap: 1/7 of the way per frame.
  const int64_t pace = FramePlan::kMaxInterval - 1;
  EXPECT_EQ(FramePlan::fluidMinWork(f), (80000 + pace - 1) / pace);
  f.workDone = 40000;
  s.stepFrames = 2;  // after this frame it must be 3/7 of the way: done already
  EXPECT_EQ(FramePlan::fluidMinWork(f), 0);
  s.stepFrames = 4;  // after this frame 5/7 of the way: 57143 (rounded up)
  EXPECT_EQ(FramePlan::fluidMinWork(f), 57143 - 40000);
  s.stepFrames = FramePlan::kMaxInterval - 2;  // the paced end: all it expects to need
  EXPECT_EQ(FramePlan::fluidMinWork(f), 80000 - 40000);
  s.stepFrames = FramePlan::kMaxInterval - 1;  // its last frame: all that is left, however much
  EXPECT_EQ(FramePlan::fluidMinWork(f), std::numeric_limits<int64_t>::max());
  FramePlan::Fluid unknown{0, &s, 0, 0};
  s.stepFrames = 0;
  EXPECT_EQ(FramePlan::fluidMinWork(unknown), 0);
}

TEST(FramePlan, AMissedFloorRaisesTheLowestPriorityIntervalFirst) {
  ActorSchedule hero, extra, other;
  std::vector<FramePlan::Deformable> d = {{5, &hero}, {0, &extra}, {0, &other}};
  ASSERT_TRUE(FramePlan::adjustIntervals(d, {true, false, false}, 0.0));
  EXPECT_EQ(hero.interval, 1);
  EXPECT_EQ(extra.interval, 1);
  EXPECT_EQ(other.interval, 2);  // among equals, the last in slot order
  other.interval = extra.interval = FramePlan::kMaxInterval;
  ASSERT_TRUE(FramePlan::adjustIntervals(d, {true, false, false}, 0.0));
  EXPECT_EQ(hero.interval, 2);  // the others are at the cap
  hero.interval = FramePlan::kMaxInterval;
  EXPECT_FALSE(FramePlan::adjustIntervals(d, {true, false, false}, 0.0));  // infeasible
}

TEST(FramePlan, ADeformablePacedByAnotherActorIsPassedOver) {
  ActorSchedule hero, nearBall, inWater;
  std::vector<FramePlan::Deformable> d = {
      {5, &hero}, {0, &nearBall, FramePlan::Pacing::EveryFrame}, {0, &inWater, FramePlan::Pacing::WithLiquids}};
  ASSERT_TRUE(FramePlan::adjustIntervals(d, {true, false, false}, 0.0));
  EXPECT_EQ(nearBall.interval, 1);
  EXPECT_EQ(inWater.interval, 1);
  EXPECT_EQ(hero.interval, 2);
  hero.interval = FramePlan::kMaxInterval;
  EXPECT_FALSE(FramePlan::adjustIntervals(d, {true, false, false}, 0.0));  // nothing left to raise
  // Their floors hold whatever the budget: they cannot lower their rates to make room.
  for (const FramePlan::Deformable& paced : {d[1], d[2]})
    EXPECT_TRUE(FramePlan::deformableDeadlines(Deadline(), *paced.schedule, 0.0, 0.0, 1, paced.ownRate()).forced);
  EXPECT_FALSE(FramePlan::deformableDeadlines(Deadline(), ActorSchedule{}, 0.0, 0.0, 1, true).forced);
}

TEST(FramePlan, IntervalsComeDownOnlyAfterCalmFramesWithRoom) {
  ActorSchedule s;
  s.interval = 3;
  s.expectedMs = 2.0;
  std::vector<FramePlan::Deformable> d = {{0, &s}};
  for (int f = 0; f < FramePlan::kCalmFrames - 1; ++f) FramePlan::adjustIntervals(d, {false}, 10.0);
  EXPECT_EQ(s.interval, 3);
  FramePlan::adjustIntervals(d, {false}, 1.0);  // no room: the count starts over
  for (int f = 0; f < FramePlan::kCalmFrames - 1; ++f) FramePlan::adjustIntervals(d, {false}, 10.0);
  EXPECT_EQ(s.interval, 3);
  FramePlan::adjustIntervals(d, {false}, 10.0);
  EXPECT_EQ(s.interval, 2);
}

using testutil::TickClock;

struct TickWorld {
  TickClock clock;
  std::unique_ptr<World> world;
  explicit TickWorld(double budgetMs, int workers = 1) {
    WorldConfig config;
    config.frameBudgetMs = budgetMs;
    config.workerCount = workers;
    config.clock = Clock{&TickClock::read, &clock};
    EXPECT_EQ(World::create(config, &world), Status::Ok) << lastError();
  }
};

DeformableDesc bar(const Vec3& position, int priority = 0) {
  DeformableDesc d;
  d.mesh = makeBoxTetMesh({10, 3, 3}, Vec3(2, 0.4, 0.4), Vec3::Zero());
  d.pose.position = position;
  d.material.youngsModulus = 1e6;
  d.solver.preconditioner = Preconditioner::BlockJacobi;
  d.priority = priority;
  return d;
}

FluidDesc box(FluidKind kind, const Vec3& origin) {
  FluidDesc d;
  d.kind = kind;
  d.grid.origin = origin;
  d.grid.h = 0.1;
  d.grid.nx = d.grid.nz = 8;
  d.grid.ny = 6;
  if (kind == FluidKind::Liquid) {
    FluidShape water;
    water.type = FluidShape::Type::Box;
    water.centre = origin + Vec3(0.4, 0.15, 0.4);
    water.halfExtents = Vec3(0.4, 0.15, 0.2);
    d.initialLiquid.push_back(water);
  } else {
    FluidEmitter e;
    e.shape.type = FluidShape::Type::Sphere;
    e.shape.centre = origin + Vec3(0.4, 0.15, 0.4);
    e.shape.radius = 0.12;
    e.velocity = Vec3(0, 0.5, 0);
    d.emitters.push_back(e);
  }
  return d;
}

// Two liquids, one smoke and three deformables (one pinned bar, two falling on a plane).
void addMixedScene(World& world) {
  FluidHandle f;
  EXPECT_EQ(world.createFluid(box(FluidKind::Liquid, Vec3(0, 0, 0)), &f), Status::Ok) << lastError();
  EXPECT_EQ(world.createFluid(box(FluidKind::Liquid, Vec3(2, 0, 0)), &f), Status::Ok) << lastError();
  EXPECT_EQ(world.createFluid(box(FluidKind::Smoke, Vec3(4, 0, 0)), &f), Status::Ok) << lastError();
  ColliderDesc ground;
  ground.shape.type = ShapeType::Plane;
  ground.shape.normal = Vec3::UnitY();
  ColliderHandle c;
  EXPECT_EQ(world.createCollider(ground, &c), Status::Ok) << lastError();
  for (int b = 0; b < 3; ++b) {
    DeformableHandle h;
    EXPECT_EQ(world.createDeformable(bar(Vec3(0, 1.0 + b, -2)), &h), Status::Ok) << lastError();
  }
}

struct FrameRecord {
  double overrunMs = 0.0;  // past the budget, beyond the frame's longest slice
  bool fluidRanWithAFloorMissed = false;
};

// Steps `frames` frames and checks, frame by frame, the plan's two guarantees where the stats
// do not say the budget was infeasible (a rate at its cap forced work): a frame ends within
// its budget plus its longest slice (and the bookkeeping ticks after it), and no fluid gets
// time while a deformable ended the frame above its floor.
void checkFrames(World& world, int frames, double budgetMs, double tickMs) {
  const double dt = 1.0 / 60.0;
  double simulated[8] = {};
  for (int frame = 0; frame < frames; ++frame) {
    ASSERT_EQ(world.step(dt), Status::Ok);
    const StepStats& s = world.lastStats();
    // Each actor's timers read the tick clock a few times after its share ends (its stats,
    // the phase laps after a solve), a tick each here and nothing measurable in real time.
    const double bookkeepingMs = 4 * tickMs * static_cast<double>(s.actors.size());
    if (!s.budgetInfeasible) {
      EXPECT_LE(s.totalMs, budgetMs + s.maxSliceMs + bookkeepingMs)
          << "frame " << frame << " at " << budgetMs << " ms, longest slice " << s.maxSliceMs;
    }
    bool fluidRan = false, floorMissed = false;
    int fluid = 0;
    for (const ActorStats& a : s.actors) {
      if (a.kind == ActorKind::Fluid) {
        fluidRan = fluidRan || a.slices > 0;
        simulated[fluid++] += a.simulatedDt;
      }
      if (a.kind == ActorKind::Deformable && a.completedStep) floorMissed = floorMissed || a.floorMissed;
    }
    if (!s.budgetInfeasible) {
      EXPECT_FALSE(fluidRan && floorMissed) << "frame " << frame << " at " << budgetMs << " ms";
    }
  }
  // Each fluid's time is simulated or pending, never lost: at most the cap's frames wait.
  for (size_t f = 0; f < world.fluidCount(); ++f) {
    EXPECT_LE(simulated[f], frames * dt + 1e-9);
    EXPECT_GE(simulated[f], (frames - 2 * FramePlan::kMaxInterval) * dt - 1e-9) << "fluid " << f << " at " << budgetMs;
  }
}

TEST(FrameBudgetPlan, TheDefaultSceneStaysWithinEachBudgetAndItsLongestSlice) {
  for (double budgetMs : {4.0, 8.0, 16.0, 33.0}) {
    TickWorld w(budgetMs);
    ASSERT_EQ(loadScene(*w.world, std::string(VP_SCENE_DIR) + "/default.json"), Status::Ok) << lastError();
    ASSERT_EQ(w.world->setFrameBudget(budgetMs), Status::Ok);  // the scene sets its own
    checkFrames(*w.world, 40, budgetMs, w.clock.tick * 1e3);
  }
}

TEST(FrameBudgetPlan, TwoLiquidsASmokeAndThreeDeformablesStayWithinEachBudget) {
  for (double budgetMs : {4.0, 8.0, 16.0, 33.0}) {
    TickWorld w(budgetMs);
    addMixedScene(*w.world);
    checkFrames(*w.world, 40, budgetMs, w.clock.tick * 1e3);
  }
}

// Two bars under a 1.2 ms tick budget, each needing more ticks to reach its floor than half the
// budget leaves: a hero of priority 1 at y = 2 and an extra of priority 0 at y = 4.
struct TwoBars {
  TickWorld w{1.2};
  DeformableHandle hero, extra;
  int heroMax = 1, extraMax = 1;  // the largest intervals seen

  TwoBars() {
    DeformableDesc heroDesc = bar(Vec3(0, 2, 0), 1);
    DeformableDesc extraDesc = bar(Vec3(0, 4, 0), 0);
    for (DeformableDesc* d : {&heroDesc, &extraDesc}) d->solver.tolerance = d->solver.targetResidual = 1e-6;
    EXPECT_EQ(w.world->createDeformable(heroDesc, &hero), Status::Ok) << lastError();
    EXPECT_EQ(w.world->createDeformable(extraDesc, &extra), Status::Ok) << lastError();
  }
  void step() {
    ASSERT_EQ(w.world->step(1.0 / 60.0), Status::Ok);
    for (const ActorStats& a : w.world->lastStats().actors) {
      if (a.kind != ActorKind::Deformable) continue;
      int& most = a.priority == 1 ? heroMax : extraMax;
      most = std::max(most, a.interval);
    }
  }
};

TEST(FrameBudgetPlan, ATightBudgetRaisesTheLowerPriorityIntervalFirst) {
  TwoBars bars;
  for (int frame = 0; frame < 20; ++frame) {
    bars.step();
    if (bars.extraMax < FramePlan::kMaxInterval) {
      EXPECT_EQ(bars.heroMax, 1) << "frame " << frame;
    }
  }
  EXPECT_GT(bars.extraMax, 1);
}

// The same two bars, the lower-priority one on a static shelf with a dynamic ball resting on
// it: that bar keeps stepping every frame (it solves its contacts with the ball only over the
// frame's dt) and reaches its floor, and the hero's rate is lowered instead.
TEST(FrameBudgetPlan, ADeformableWithinReachOfADynamicBodyKeepsSteppingEveryFrame) {
  TwoBars bars;
  ColliderDesc shelf;
  shelf.bodyType = BodyType::Static;
  shelf.shape.type = ShapeType::Box;
  shelf.shape.halfExtents = Vec3(1.5, 0.1, 0.5);
  shelf.pose.position = Vec3(1.0, 3.9, 0.2);
  ColliderDesc ball;
  ball.bodyType = BodyType::Dynamic;
  ball.shape.type = ShapeType::Sphere;
  ball.shape.radius = 0.1;
  ball.pose.position = Vec3(1.0, 4.5, 0.2);  // on the bar's top face, at its middle
  ColliderHandle shelfHandle, ballHandle;
  ASSERT_EQ(bars.w.world->createCollider(shelf, &shelfHandle), Status::Ok) << lastError();
  ASSERT_EQ(bars.w.world->createCollider(ball, &ballHandle), Status::Ok) << lastError();
  for (int frame = 0; frame < 20; ++frame) bars.step();
  EXPECT_EQ(bars.extraMax, 1);
  EXPECT_GT(bars.heroMax, 1);
  // Its solve reached its floor every frame (a solve cut above it threw the ball up).
  EXPECT_LT(bars.w.world->collider(ballHandle)->pose().position.y(), 4.6);
}

TEST(FrameBudgetPlan, ABudgetTooSmallForAnyFloorCapsTheRatesAndSaysSo) {
  TickWorld w(0.05);  // half a tick: nothing fits
  addMixedScene(*w.world);
  const double dt = 1.0 / 60.0;
  bool infeasible = false;
  double simulated = 0.0;
  const int frames = 4 * FramePlan::kMaxInterval;
  int maxInterval = 1;
  for (int frame = 0; frame < frames; ++frame) {
    ASSERT_EQ(w.world->step(dt), Status::Ok);
    const StepStats& s = w.world->lastStats();
    infeasible = infeasible || s.budgetInfeasible;
    for (const ActorStats& a : s.actors) {
      EXPECT_FALSE(a.diverged);
      maxInterval = std::max(maxInterval, a.interval);
    }
    simulated += s.actors.back().simulatedDt;  // the last fluid
  }
  EXPECT_TRUE(infeasible);
  EXPECT_EQ(maxInterval, FramePlan::kMaxInterval);
  // The last fluid's time: at most its step in progress and the frames since it began (each
  // at most kMaxInterval) are not simulated yet.
  EXPECT_GE(simulated, (frames - 2 * FramePlan::kMaxInterval) * dt - 1e-9);
  // A budget change takes effect on the next frame: unlimited, every actor completes a step
  // (the one in progress, then one with the time since it began), and no time was lost.
  ASSERT_EQ(w.world->setFrameBudget(0.0), Status::Ok);
  for (int frame = 0; frame < 2; ++frame) {
    ASSERT_EQ(w.world->step(dt), Status::Ok);
    simulated += w.world->lastStats().actors.back().simulatedDt;
  }
  for (const ActorStats& a : w.world->lastStats().actors) EXPECT_TRUE(a.completedStep);
  EXPECT_EQ(w.world->lastStats().budgetMs, 0.0);
  EXPECT_NEAR(simulated, (frames + 2) * dt, 1e-9);
}

}  // namespace
}  // namespace vp

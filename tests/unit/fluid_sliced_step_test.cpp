// A fluid step run in slices (fluid_actor.h): split into 1 to 8 pieces it gives bitwise the
// result of the same step run whole, for smoke and liquid with a moving collider and a
// two-way coupled body; between pieces readers see the last completed step.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>

#include "collide/face_coverage.h"
#include "fluid/fluid_actor.h"

namespace vp {
namespace {

// Every reading advances a second: any budget has expired by the first slice, so a piece
// runs until it has done its minWork.
struct SecondClock {
  double seconds = 0.0;
  static double read(void* self) { return static_cast<SecondClock*>(self)->seconds += 1.0; }
};

FluidDesc smallFluid(FluidKind kind) {
  FluidDesc d;
  d.kind = kind;
  d.grid.h = 0.1;
  d.grid.nx = 12, d.grid.ny = 10, d.grid.nz = 8;
  d.density = kind == FluidKind::Liquid ? 1000.0 : 1.2;
  d.solver.pressureTolerance = 1e-6;
  d.twoWayCoupling = true;
  d.solver.advection = AdvectionScheme::MacCormack;
  d.solver.samplesPerSlice = 250;  // several slabs per advection pass
  if (kind == FluidKind::Liquid) {
    FluidShape water;
    water.type = FluidShape::Type::Box;
    water.halfExtents = Vec3(0.6, 0.25, 0.4);
    water.centre = Vec3(0.6, 0.25, 0.4);
    d.initialLiquid.push_back(water);
  } else {
    FluidEmitter e;
    e.shape.type = FluidShape::Type::Sphere;
    e.shape.centre = Vec3(0.6, 0.15, 0.4);
    e.shape.radius = 0.15;
    e.densityRate = 2.0;
    e.temperature = 5.0;
    e.velocity = Vec3(0, 1.0, 0);
    d.emitters.push_back(e);
  }
  return d;
}

// A paddle turning through the fluid and a dynamic ball; each step moves the paddle.
struct Colliders {
  PreparedCollider paddle, ball;
  explicit Colliders(int step) {
    ColliderShape p;
    p.kind = ShapeKind::Box;
    p.halfExtents = Vec3(0.35, 0.1, 0.04);
    const double angle = 0.2 * step;
    p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, Vec3::UnitY()));
    p.translation = Vec3(0.6, 0.3, 0.4);
    p.angularVelocity = Vec3(0, 12.0, 0);
    EXPECT_EQ(prepareCollider(p, &paddle), Status::Ok) << lastError();
    ColliderShape b;
    b.kind = ShapeKind::Sphere;
    b.radius = 0.12;
    b.translation = Vec3(0.3 + 0.01 * step, 0.52, 0.4);  // above the paddle: overlapping solids cost a union
    b.linearVelocity = Vec3(0.6, -0.2, 0);
    EXPECT_EQ(prepareCollider(b, &ball), Status::Ok) << lastError();
  }
  std::vector<FluidCollider> list() const {
    return {FluidCollider{1, 1, &paddle, nullptr, false, {}}, FluidCollider{2, 1, &ball, nullptr, true, {}}};
  }
};

struct Fields {
  Array<double> u[3], smoke, heat, phi, pressure;
  std::vector<FluidColliderLoad> loads;
  explicit Fields(const FluidActor& a) {
    for (int k = 0; k < 3; ++k) u[k] = a.grid().velocity[k];
    smoke = a.smokeDensity(), heat = a.temperature(), phi = a.levelSet(), pressure = a.pressure();
    loads = a.loads();
  }
};

void expectBitwiseEqual(const Fields& a, const Fields& b, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(a.u[k] == b.u[k]) << what << ": velocity " << k;
  EXPECT_TRUE(a.smoke == b.smoke) << what << ": smoke";
  EXPECT_TRUE(a.heat == b.heat) << what << ": temperature";
  EXPECT_TRUE(a.phi == b.phi) << what << ": level set";
  EXPECT_TRUE(a.pressure == b.pressure) << what << ": pressure";
  ASSERT_EQ(a.loads.size(), b.loads.size()) << what;
  for (size_t c = 0; c < a.loads.size(); ++c) {
    EXPECT_TRUE(a.loads[c].load.force == b.loads[c].load.force) << what << ": load force";
    EXPECT_TRUE(a.loads[c].load.torque == b.loads[c].load.torque) << what << ": load torque";
    EXPECT_EQ(a.loads[c].load.addedMass, b.loads[c].load.addedMass) << what << ": added mass";
  }
}

void slicedEqualsWhole(FluidKind kind, int workers) {
  auto tasks = TaskSystem::create(TaskHooks{}, workers);
  SecondClock clock;
  const Clock ticking{&SecondClock::read, &clock};
  std::unique_ptr<FluidActor> whole;
  ASSERT_EQ(FluidActor::create(smallFluid(kind), *tasks, &whole), Status::Ok) << lastError();
  std::vector<std::unique_ptr<FluidActor>> sliced(8);
  for (auto& a : sliced) ASSERT_EQ(FluidActor::create(smallFluid(kind), *tasks, &a), Status::Ok);
  const double dt = 0.1;  // long enough for several CFL sub-steps
  for (int step = 0; step < 4; ++step) {
    const Colliders colliders(step);
    FluidStepInput input;
    input.dt = dt;
    input.gravity = Vec3(0, -9.81, 0);
    input.tasks = tasks.get();
    input.colliders = colliders.list();
    const Fields before(*whole);
    ActorStats wholeStats;
    whole->step(input, &wholeStats, nullptr);
    ASSERT_FALSE(wholeStats.diverged);
    const int slices = whole->lastStepSlices();
    const int64_t work = whole->stepWork().last();
    std::printf("step %d: %d slices, work %lld, %d pressure iterations\n", step, slices,
                static_cast<long long>(work), wholeStats.phase(Phase::Pressure).iterations);
    ASSERT_GT(slices, 8);
    const Fields after(*whole);
    for (int pieces = 1; pieces <= 8; ++pieces) {
      FluidActor& actor = *sliced[pieces - 1];
      SliceBudget budget;
      budget.share = Deadline(ticking, 1.0);
      budget.minWork = (work + pieces - 1) / pieces;
      int calls = 0;
      bool completed = false;
      while (!completed) {
        ActorStats stats;
        const int64_t workBefore = actor.stepInProgress() ? actor.stepWork().done() : 0;
        completed = actor.advance(input, budget, &stats);
        ++calls;
        ASSERT_LE(calls, pieces) << "a step in " << pieces << " pieces";
        if (!completed) {
          // A piece stops only once it has done its share of the work.
          EXPECT_GE(actor.stepWork().done() - workBefore, budget.minWork) << "piece " << calls;
          EXPECT_LT(stats.progress, 1.0);
          expectBitwiseEqual(Fields(actor), before, "a reader between slices");
        }
      }
      EXPECT_EQ(calls > 1, pieces > 1) << "a share below the whole step's work splits it";
      expectBitwiseEqual(Fields(actor), after, pieces == 1 ? "1 piece" : "several pieces");
      EXPECT_EQ(actor.lastStepSlices(), slices);
      EXPECT_EQ(actor.stepWork().last(), work);
    }
  }
}

TEST(FluidSlicedStep, SmokeInPiecesIsBitwiseTheWholeStep) { slicedEqualsWhole(FluidKind::Smoke, 1); }

TEST(FluidSlicedStep, LiquidInPiecesIsBitwiseTheWholeStep) { slicedEqualsWhole(FluidKind::Liquid, 1); }

TEST(FluidSlicedStep, LiquidInPiecesOnTwoWorkersIsBitwiseTheWholeStep) { slicedEqualsWhole(FluidKind::Liquid, 2); }

TEST(FluidSlicedStep, TheLoadsOnACoupledBodyAreThoseOfTheLastCompletedStep) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  SecondClock clock;
  std::unique_ptr<FluidActor> actor;
  ASSERT_EQ(FluidActor::create(smallFluid(FluidKind::Liquid), *tasks, &actor), Status::Ok);
  const Colliders colliders(0);
  FluidStepInput input;
  input.gravity = Vec3(0, -9.81, 0);
  input.tasks = tasks.get();
  input.colliders = colliders.list();
  EXPECT_TRUE(actor->loads().empty());  // no step has completed
  ActorStats stats;
  actor->step(input, &stats, nullptr);
  const std::vector<FluidColliderLoad> first = actor->loads();
  ASSERT_EQ(first.size(), 1u);  // the ball is the one dynamic collider
  EXPECT_GT(first[0].load.force.y(), 0.0);  // the half-submerged ball is buoyed up
  SliceBudget oneSlice;
  oneSlice.share = Deadline(Clock{&SecondClock::read, &clock}, 1.0);
  oneSlice.minWork = 1;
  ASSERT_FALSE(actor->advance(input, oneSlice, &stats));
  ASSERT_TRUE(actor->stepInProgress());
  EXPECT_EQ(actor->loads()[0].load.force, first[0].load.force);
  EXPECT_FALSE(actor->editFields([](FluidActor::EditableFields&) {}));  // refused mid-step
}

}  // namespace
}  // namespace vp

namespace vp {
namespace {

// A step that needs more sub-steps than the last one is expected to take that many sub-steps'
// work as soon as its plan is made (the frame plan paces it by that, core/work_progress.h).
TEST(FluidSlicedStep, TheExpectedWorkFollowsTheSubstepCount) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  SecondClock clock;
  const Clock ticking{&SecondClock::read, &clock};
  std::unique_ptr<FluidActor> actor;
  ASSERT_EQ(FluidActor::create(smallFluid(FluidKind::Liquid), *tasks, &actor), Status::Ok) << lastError();
  FluidStepInput input;
  input.dt = 0.1;
  input.gravity = Vec3(0, -9.81, 0);
  input.tasks = tasks.get();
  ActorStats calm;
  actor->step(input, &calm, nullptr);
  ASSERT_EQ(calm.substeps, 1);
  const int64_t perSubstep = actor->stepWork().expectedPerPart();
  ASSERT_GT(perSubstep, 0);
  // 7 m/s over dt = 0.1 s is 3.5 cells of h = 0.1 at a CFL number of 2 per sub-step: 4 sub-steps.
  ASSERT_TRUE(actor->editFields([](FluidActor::EditableFields& f) {
    for (double& u : f.grid.velocity[0]) u = 7.0;
  }));
  SliceBudget budget;
  budget.share = Deadline(ticking, 1.0);
  budget.minWork = 1;  // one slice per call
  int64_t expectedAfterPlan = -1;
  ActorStats stats;
  while (!actor->advance(input, budget, &stats)) {
    if (expectedAfterPlan < 0 && actor->stepWork().parts() == 4) expectedAfterPlan = actor->stepWork().expected();
    stats = ActorStats{};
  }
  ASSERT_EQ(stats.substeps, 4);
  ASSERT_GT(expectedAfterPlan, 0) << "the plan's sub-step count never reached the expectation";
  const int64_t actual = actor->stepWork().last();
  std::printf("per sub-step %lld, expected after the plan %lld, took %lld\n", static_cast<long long>(perSubstep),
              static_cast<long long>(expectedAfterPlan), static_cast<long long>(actual));
  // Four sub-steps' worth on top of the head: the face fraction update's three slices, each
  // counted as one pass over the grid when no collider gives them samples, and its empty pass
  // list (no collider moved), one sample ...
  EXPECT_GE(expectedAfterPlan, 4 * perSubstep);
  EXPECT_LE(expectedAfterPlan, 4 * perSubstep + 3 * actor->grid().cellCount() + 1);
  // ... which is what the step took, but for the pressure iterations the flow added: a
  // per-step expectation would have been about a quarter of it.
  EXPECT_GT(static_cast<double>(expectedAfterPlan), 0.9 * static_cast<double>(actual));
}

}  // namespace
}  // namespace vp

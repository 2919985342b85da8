// The per-frame budget with an injected clock (deterministic): solvers stop when it is spent,
// say so, keep the iterate they reached, warm-start, and catch up over the following frames; the budget is
// shared between actors by the world's policy (each gets an equal share of what is left, or
// more when the actors after it are expected to need less).
#include <gtest/gtest.h>

#include <cstdio>

#include "geometry/box_tet_mesh.h"
#include "tick_clock.h"
#include "world.h"

namespace vp {
namespace {

using testutil::TickClock;

struct BudgetWorld {
  TickClock clock;
  std::unique_ptr<World> world;
  std::vector<DeformableHandle> bars;

  // One pinned bar per entry of maxIterations (the solver's iteration cap for that bar).
  BudgetWorld(double budgetMs, std::vector<int> maxIterations) {
    WorldConfig config;
    config.frameBudgetMs = budgetMs;
    config.clock = Clock{&TickClock::read, &clock};
    EXPECT_EQ(World::create(config, &world), Status::Ok);
    for (int b = 0; b < static_cast<int>(maxIterations.size()); ++b) {
      DeformableDesc d;
      d.mesh = makeBoxTetMesh({12, 3, 3}, Vec3(3, 0.5, 0.5), Vec3::Zero());
      d.pose.position = Vec3(0, 2.0 * b, 0);
      d.material.youngsModulus = 1e7;
      d.solver.tolerance = 1e-8;
      d.solver.maxIterations = maxIterations[b];
      d.solver.preconditioner = Preconditioner::BlockJacobi;  // many iterations: easy to cut
      // No accuracy floor: these tests are about cutting solves and sharing the budget above
      // the floor (frame_plan_test.cpp covers the floors and the rates they lower).
      d.solver.targetResidual = 1.0;
      DeformableHandle h;
      EXPECT_EQ(world->createDeformable(std::move(d), &h), Status::Ok);
      DeformableBody& body = *world->deformable(h);
      std::vector<int32_t> left;
      for (int32_t i = 0; i < body.nodeCount(); ++i)
        if (body.restPositions()[3 * i] == 0.0) left.push_back(i);
      body.setPinned(left.data(), static_cast<int64_t>(left.size()), true);
      bars.push_back(h);
    }
  }
  const PhaseStats& solve(int actor) const { return world->lastStats().actors[1 + actor].phase(Phase::Solve); }
};

TEST(FrameBudget, SolverStopsAtTheBudgetFlagsItAndNeverOverrunsByMoreThanAnIteration) {
  const double budgetMs = 5.0;  // 50 ticks
  BudgetWorld w(budgetMs, {10000});
  ASSERT_EQ(w.world->step(1.0 / 60.0), Status::Ok);
  const StepStats& stats = w.world->lastStats();
  EXPECT_TRUE(w.solve(0).budgetCut);
  EXPECT_TRUE(stats.budgetCut);
  EXPECT_GT(w.solve(0).iterations, 10);
  EXPECT_LT(w.solve(0).iterations, 50);
  // The last iteration started before the deadline; after it only a few clock readings
  // (phase timers, integration, the step total) follow: one iteration's tick plus those.
  EXPECT_GE(stats.totalMs, budgetMs);
  EXPECT_LE(stats.totalMs, budgetMs + 6 * 0.1);
}

TEST(FrameBudget, ACutSolveKeepsExactlyTheIterateItReached) {
  // The cut must not throw the work away or fall back to the warm start: the state after a
  // solve cut at n iterations equals the state after a solve capped at n iterations.
  BudgetWorld cut(5.0, {10000});
  ASSERT_EQ(cut.world->step(1.0 / 60.0), Status::Ok);
  ASSERT_TRUE(cut.solve(0).budgetCut);
  const int n = cut.solve(0).iterations;
  BudgetWorld capped(0.0, {n});
  ASSERT_EQ(capped.world->step(1.0 / 60.0), Status::Ok);
  ASSERT_FALSE(capped.solve(0).budgetCut);
  ASSERT_EQ(capped.solve(0).iterations, n);
  EXPECT_EQ(cut.solve(0).residual, capped.solve(0).residual);
  const DeformableBody& a = *cut.world->deformable(cut.bars[0]);
  const DeformableBody& b = *capped.world->deformable(capped.bars[0]);
  for (int32_t i = 0; i < 3 * a.nodeCount(); ++i) ASSERT_EQ(a.positions()[i], b.positions()[i]) << "coordinate " << i;
}

TEST(FrameBudget, SolvesWarmStartFromTheCurrentVelocity) {
  // A free body gliding without gravity solves to v' = v. Started from v the solve has
  // nothing to do; started cold (from zero) it would iterate every frame.
  TickClock clock;
  WorldConfig config;
  config.gravity = Vec3::Zero();
  config.frameBudgetMs = 5.0;
  config.clock = Clock{&TickClock::read, &clock};
  std::unique_ptr<World> world;
  ASSERT_EQ(World::create(config, &world), Status::Ok);
  DeformableDesc d;
  d.mesh = makeBoxTetMesh({4, 2, 2}, Vec3(1, 0.5, 0.5), Vec3::Zero());
  d.linearVelocity = Vec3(2.0, 0.0, 0.0);
  d.solver.preconditioner = Preconditioner::BlockJacobi;
  DeformableHandle h;
  ASSERT_EQ(world->createDeformable(std::move(d), &h), Status::Ok);
  for (int frame = 0; frame < 10; ++frame) {
    ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
    const PhaseStats& solve = world->lastStats().actors[1].phase(Phase::Solve);
    EXPECT_LE(solve.iterations, 1) << "frame " << frame;
    EXPECT_FALSE(solve.budgetCut);
  }
  EXPECT_NEAR(world->deformable(h)->positions()[0], 10 * 2.0 / 60.0, 1e-6);
}

double tipY(const BudgetWorld& w) {
  const DeformableBody& bar = *w.world->deformable(w.bars[0]);
  return bar.positions()[3 * (bar.nodeCount() - 1) + 1];
}

TEST(FrameBudget, CutSolvesKeepTheirIterateAndTheMotionCatchesUp) {
  // Each frame of this falling, pinned bar needs ~180 block-Jacobi iterations to 1e-8.
  // Run A has no budget; run B has 5 ms (~45 iterations) for three frames, then 50 ms.
  BudgetWorld a(0.0, {10000}), b(5.0, {10000});
  for (int frame = 0; frame < 90; ++frame) {
    if (frame == 3) b.world->setFrameBudget(50.0);
    ASSERT_EQ(a.world->step(1.0 / 60.0), Status::Ok);
    ASSERT_EQ(b.world->step(1.0 / 60.0), Status::Ok);
    if (frame < 3) {
      EXPECT_TRUE(b.solve(0).budgetCut);
      EXPECT_LT(b.solve(0).residual, 1.0);  // the cut solve still improved on its warm start
    } else {
      EXPECT_FALSE(b.solve(0).budgetCut) << "frame " << frame;
    }
  }
  // The cut frames left the bar a little behind; damping and later converged frames bring
  // it back onto the unbudgeted trajectory.
  const DeformableBody& bar = *a.world->deformable(a.bars[0]);
  const double sag = bar.restPositions()[3 * (bar.nodeCount() - 1) + 1] - tipY(a);
  ASSERT_GT(sag, 1e-3);
  EXPECT_LT(std::abs(tipY(a) - tipY(b)), 0.02 * sag);
}

TEST(FrameBudget, TwoActorsShareTheBudgetByThePolicy) {
  // Policy: actors run in order, each gets an equal share of what is left when its turn
  // comes. With both cut, the first gets about half the budget and the second the rest.
  BudgetWorld w(10.0, {10000, 10000});
  ASSERT_EQ(w.world->step(1.0 / 60.0), Status::Ok);
  const auto& actors = w.world->lastStats().actors;
  ASSERT_EQ(actors.size(), 3u);
  EXPECT_TRUE(w.solve(0).budgetCut);
  EXPECT_TRUE(w.solve(1).budgetCut);
  const double first = actors[1].totalMs, second = actors[2].totalMs;
  EXPECT_NEAR(first, 5.0, 1.0);
  EXPECT_NEAR(second, 5.0, 1.0);
  EXPECT_LE(w.world->lastStats().totalMs, 10.0 + 1.0);
  // An actor that finishes early passes its unused time on: here the first bar stops at its
  // 5-iteration cap, and the second gets nearly the whole budget.
  BudgetWorld early(10.0, {5, 10000});
  ASSERT_EQ(early.world->step(1.0 / 60.0), Status::Ok);
  EXPECT_FALSE(early.solve(0).budgetCut);
  EXPECT_EQ(early.solve(0).iterations, 5);
  EXPECT_TRUE(early.solve(1).budgetCut);
  EXPECT_GT(early.world->lastStats().actors[2].totalMs, 8.0);
}

TEST(FrameBudget, ADeformableGetsMoreThanItsEqualShareWhenTheOnesAfterItAreCheap) {
  // The first bar never converges, the second stops at 5 iterations. From the second frame on
  // the first leaves the second 1.25 times its smoothed cost instead of half the budget, and
  // its solve ends early enough for its own step's work after the solve (frame_plan.h).
  BudgetWorld w(10.0, {10000, 5});
  double secondExpected = -1.0;
  for (int f = 0; f < 4; ++f) {
    ASSERT_EQ(w.world->step(1.0 / 60.0), Status::Ok);
    const auto& actors = w.world->lastStats().actors;
    EXPECT_TRUE(w.solve(0).budgetCut);
    if (f == 0) {
      EXPECT_NEAR(actors[1].totalMs, 5.0, 1.0);  // nothing measured yet: equal shares
    } else {
      const double tail = FramePlan::kMargin * w.world->deformable(w.bars[0])->schedule().tailMs;
      EXPECT_LE(actors[1].totalMs, 10.0 - 1.25 * secondExpected) << "frame " << f;
      EXPECT_GE(actors[1].totalMs, 10.0 - 1.25 * secondExpected - tail - 0.5) << "frame " << f;
      // Of the time left after the contact detection that precedes both steps.
      EXPECT_GT(actors[1].totalMs, 8.0 - w.world->lastStats().deformableContactMs);
      EXPECT_GE(w.solve(1).iterations, 4) << "frame " << f;  // the cheap bar is not starved
    }
    EXPECT_LE(w.world->lastStats().totalMs, 10.0 + 1.0);
    secondExpected = secondExpected < 0.0 ? actors[2].totalMs : secondExpected + 0.2 * (actors[2].totalMs - secondExpected);
  }
}

}  // namespace
}  // namespace vp

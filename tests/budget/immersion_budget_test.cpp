// A body in a liquid whose steps span several frames under a frame budget (frame_plan.h's
// pacing) floats as it does unbudgeted: it steps when the liquid completes a step, over the
// time the liquid's load was computed for (FramePlan::Pacing::WithLiquids); it takes the
// hydrostatic part of the load anew at each of its steps and cancels only the added-mass
// reaction the dynamic part shows (deform/fluid_immersion.h). Held whole over the frames
// between, the load was a delayed spring and the stabilization pushed with forces nothing
// exerted: a jelly dropped in was thrown out of the tank, higher than it fell from; held
// over frames of the body's own steps, the dynamic part kept it bobbing or on the floor.
// Tick clock: deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "../unit/liquid_tank_world.h"
#include "deform/deformable_body.h"
#include "geometry/box_tet_mesh.h"
#include "tick_clock.h"
#include "world.h"

namespace vp {
namespace {

constexpr double kFill = 0.5, kDensity = 600.0, kGravity = 9.81;
const Vec3 kBlock(0.3, 0.2, 0.3);

struct DropRecord {
  double releaseEnergy = 0.0, mostEnergy = 0.0;  // kinetic + gravitational, J
  double lowest = 1e30, highest = -1e30;         // the centre's height over the last second
  int fluidIntervalMax = 1;
  bool diverged = false;
};

// A jelly block of density kDensity released at rest with its bottom `drop` above the surface
// of an n³ tank of 1 m filled to kFill (open at the top, over a ground just under its floor),
// stepped for `frames` frames of 1/60 s under a tick-clock budget of budgetMs.
DropRecord dropIntoTank(double budgetMs, double drop, int frames) {
  DropRecord r;
  testutil::TickClock clock;
  WorldConfig config;
  config.workerCount = 2;
  config.clock = clock.clock();
  config.frameBudgetMs = budgetMs;
  std::unique_ptr<World> world;
  EXPECT_EQ(World::create(config, &world), Status::Ok) << lastError();
  if (!world) return r;
  FluidDesc tank = testutil::liquidTank(24, 24, 24, 1.0 / 24, kFill);
  tank.sides[3] = DomainSide::Open;
  tank.solver.pressureTolerance = 1e-6;
  FluidHandle fluid;
  EXPECT_EQ(world->createFluid(tank, &fluid), Status::Ok) << lastError();
  ColliderDesc ground;
  ground.bodyType = BodyType::Static;
  ground.shape.type = ShapeType::Box;
  ground.shape.halfExtents = Vec3(2.0, 0.5, 2.0);
  ground.pose.position = Vec3(0.5, -0.501, 0.5);
  ColliderHandle groundHandle;
  EXPECT_EQ(world->createCollider(ground, &groundHandle), Status::Ok) << lastError();
  // The tank's walls, just outside the fluid's domain: its sides hold the liquid, not bodies,
  // and a floating block drifts (nothing holds it sideways); without them it drifted out
  // through a side and fell to the ground.
  for (int wall = 0; wall < 4; ++wall) {
    ColliderDesc c;
    c.bodyType = BodyType::Static;
    c.shape.type = ShapeType::Box;
    const bool acrossX = wall < 2;
    c.shape.halfExtents = acrossX ? Vec3(0.1, 0.6, 0.7) : Vec3(0.7, 0.6, 0.1);
    const double centre = wall % 2 == 0 ? -0.101 : 1.101;
    c.pose.position = acrossX ? Vec3(centre, 0.5, 0.5) : Vec3(0.5, 0.5, centre);
    ColliderHandle handle;
    EXPECT_EQ(world->createCollider(c, &handle), Status::Ok) << lastError();
  }
  DeformableDesc jelly;
  jelly.mesh = makeBoxTetMesh({3, 2, 3}, kBlock, Vec3(0.35, kFill + drop, 0.35));
  jelly.material.youngsModulus = 2e5;
  jelly.material.poissonRatio = 0.3;
  jelly.material.density = kDensity;
  DeformableHandle handle;
  EXPECT_EQ(world->createDeformable(jelly, &handle), Status::Ok) << lastError();
  const DeformableBody& body = *world->deformable(handle);
  auto energyAndCentre = [&](double* centre) {
    double energy = 0.0, mass = 0.0, height = 0.0;
    for (int32_t i = 0; i < body.nodeCount(); ++i) {
      const double m = body.nodeMasses()[i], y = body.positions()[3 * i + 1];
      const Vec3 v(body.velocities()[3 * i], body.velocities()[3 * i + 1], body.velocities()[3 * i + 2]);
      energy += 0.5 * m * v.squaredNorm() + m * kGravity * y;
      mass += m;
      height += m * y;
    }
    *centre = height / mass;
    return energy;
  };
  double centre = 0.0;
  r.releaseEnergy = r.mostEnergy = energyAndCentre(&centre);
  for (int f = 0; f < frames; ++f) {
    EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok) << lastError();
    r.mostEnergy = std::max(r.mostEnergy, energyAndCentre(&centre));
    if (f >= frames - 60) {
      r.lowest = std::min(r.lowest, centre);
      r.highest = std::max(r.highest, centre);
    }
    for (const ActorStats& a : world->lastStats().actors) {
      r.diverged = r.diverged || a.diverged;
      if (a.kind == ActorKind::Fluid) r.fluidIntervalMax = std::max(r.fluidIntervalMax, a.interval);
    }
  }
  return r;
}

// Dropped from half a metre above the water, the jelly cannot end up with more energy than it
// was released with (the liquid started at rest, and nothing else does work on it); it comes
// to float, centred where its weight is the weight of the liquid it displaces: 60% of its
// height under the surface, which its displacement raises by that volume over the tank's area.
// At a 4 ms budget the liquid is at its rate cap: its steps span kMaxInterval - 1 or
// kMaxInterval frames and the jelly steps with it, five or six steps per bobbing period; it
// floats there too, where stepped at its own rate under the held load it lay on the floor.
TEST(ImmersionUnderBudget, ALightJellyDroppedIntoATankWhoseStepsSpanFramesFloats) {
  const double submerged = kDensity / 1000.0 * kBlock.y();
  const double floating = kFill + submerged * kBlock.x() * kBlock.z() - submerged + 0.5 * kBlock.y();
  for (double budgetMs : {4.0, 8.0, 16.0, 33.0}) {
    const DropRecord r = dropIntoTank(budgetMs, 0.5, 480);
    std::printf("budget %.0f ms: fluid steps spanned up to %d frames; most energy %+.3f J over the release's "
                "%.2f J; centre over the last second %.3f..%.3f m (floating %.3f m)\n",
                budgetMs, r.fluidIntervalMax, r.mostEnergy - r.releaseEnergy, r.releaseEnergy, r.lowest, r.highest,
                floating);
    EXPECT_GE(r.fluidIntervalMax, 4) << "the budget must make the fluid's steps span frames";
    EXPECT_FALSE(r.diverged);
    // Round-off only: the bound is exact, and backward Euler only takes energy away.
    EXPECT_LE(r.mostEnergy, r.releaseEnergy * (1.0 + 1e-9));
    // A quarter of the block's height: the bobbing has settled to less.
    EXPECT_GT(r.lowest, floating - 0.25 * kBlock.y());
    EXPECT_LT(r.highest, floating + 0.25 * kBlock.y());
  }
}

}  // namespace
}  // namespace vp

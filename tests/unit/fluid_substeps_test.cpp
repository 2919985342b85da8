// A fluid step reports the CFL sub-steps it took (ActorStats::substeps): one while nothing
// moves, ceil(speed dt / (cflNumber h)) for a collider sweeping through the domain, never more
// than maxSubsteps.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "collide/face_coverage.h"
#include "fluid/fluid_actor.h"

namespace vp {
namespace {

// The first step of a fresh smoke domain at rest, with a sphere moving at `speed` along x.
int firstStepSubsteps(double speed) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  FluidDesc d;
  d.kind = FluidKind::Smoke;
  d.grid.h = 1.0 / 16;
  d.grid.nx = d.grid.ny = d.grid.nz = 16;
  std::unique_ptr<FluidActor> actor;
  if (FluidActor::create(d, *tasks, &actor) != Status::Ok) return -1;
  ColliderShape sphere;
  sphere.kind = ShapeKind::Sphere;
  sphere.radius = 0.1;
  sphere.translation = Vec3(0.5, 0.5, 0.5);
  sphere.linearVelocity = Vec3(speed, 0, 0);
  PreparedCollider prepared;
  if (prepareCollider(sphere, &prepared) != Status::Ok) return -1;
  FluidStepInput input;
  input.dt = 1.0 / 60.0;
  input.tasks = tasks.get();
  input.colliders = {FluidCollider{1, 1, &prepared, nullptr, false, {}}};
  ActorStats stats;
  actor->step(input, &stats, nullptr);
  return stats.completedStep ? stats.substeps : -1;
}

TEST(FluidSubsteps, OneAtRestThenAsTheFastestMotionNeedsUpToTheCap) {
  const FluidSolverSettings defaults;
  const double cellsPerStepAtOneMetrePerSecond = (1.0 / 60.0) / (1.0 / 16);
  EXPECT_EQ(firstStepSubsteps(0.0), 1);
  for (double speed : {10.0, 20.0}) {
    const int expected = static_cast<int>(std::ceil(speed * cellsPerStepAtOneMetrePerSecond / defaults.cflNumber));
    ASSERT_LT(expected, defaults.maxSubsteps);
    EXPECT_EQ(firstStepSubsteps(speed), expected) << "speed " << speed;
  }
  EXPECT_EQ(firstStepSubsteps(100.0), defaults.maxSubsteps);
}

}  // namespace
}  // namespace vp

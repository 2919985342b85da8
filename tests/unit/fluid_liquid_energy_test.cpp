// A closed, inviscid dam break (a column of water falling around a box obstacle in a closed
// tank, the geometry of BM_FluidLiquidStep) against the one invariant it has: nothing does work
// on the liquid but gravity, so its mechanical energy (kinetic plus potential) can only fall.
// With the level set advected by MacCormack it rose step after step, to 1.28 times the start at
// 32^3 after 4 s, and the tank never settled (the sub-steps stayed at the CFL rule's 2-3 for
// speeds of 5-8 m/s); kLevelSetAdvection (fluid_desc.h) is what this test holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "collide/face_coverage.h"
#include "fluid/fluid_actor.h"
#include "fluid_liquid_test_util.h"

namespace vp {
namespace {

constexpr double kGravity = 9.81;
constexpr double kDensity = 1000.0;

// Kinetic plus potential energy of the liquid cells (phi < 0) outside `solid`, each cell a
// point mass at its centre moving with the mean of its faces' velocities.
double mechanicalEnergy(const MacGrid& g, const Array<double>& phi, const Aabb& solid) {
  const double h = g.spec.h, mass = kDensity * h * h * h;
  double e = 0.0;
  for (int k = 0; k < g.spec.nz; ++k)
    for (int j = 0; j < g.spec.ny; ++j)
      for (int i = 0; i < g.spec.nx; ++i) {
        const Vec3 x = g.cellCentre(i, j, k);
        if (!(phi[g.cellIndex(i, j, k)] < 0.0) || solid.overlaps(Aabb{x, x})) continue;
        const double u = 0.5 * (g.velocity[0][g.faceIndex(0, i, j, k)] + g.velocity[0][g.faceIndex(0, i + 1, j, k)]);
        const double v = 0.5 * (g.velocity[1][g.faceIndex(1, i, j, k)] + g.velocity[1][g.faceIndex(1, i, j + 1, k)]);
        const double w = 0.5 * (g.velocity[2][g.faceIndex(2, i, j, k)] + g.velocity[2][g.faceIndex(2, i, j, k + 1)]);
        e += mass * (0.5 * (u * u + v * v + w * w) + kGravity * x.y());
      }
  return e;
}

TEST(FluidLiquidEnergy, AClosedInviscidDamBreakLosesEnergyAndSettles) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const int n = 32;
  FluidDesc d;
  d.kind = FluidKind::Liquid;
  d.grid.h = 1.0 / n;
  d.grid.nx = d.grid.ny = d.grid.nz = n;
  d.density = kDensity;
  FluidShape column;
  column.type = FluidShape::Type::Box;
  column.centre = Vec3(0.2, 0.4, 0.5);
  column.halfExtents = Vec3(0.2, 0.4, 0.5);
  d.initialLiquid.push_back(column);
  std::unique_ptr<FluidActor> actor;
  ASSERT_EQ(FluidActor::create(d, *tasks, &actor), Status::Ok) << lastError();
  ColliderShape box;
  box.kind = ShapeKind::Box;
  box.halfExtents = Vec3(0.08, 0.15, 0.2);
  box.translation = Vec3(0.65, 0.15, 0.5);
  PreparedCollider obstacle;
  ASSERT_EQ(prepareCollider(box, &obstacle), Status::Ok);
  // The cells a cut cell could leave liquid inside the box are left out of the measure.
  const Aabb solid{box.translation - box.halfExtents - Vec3::Constant(d.grid.h),
                   box.translation + box.halfExtents + Vec3::Constant(d.grid.h)};
  FluidStepInput input;
  input.dt = 1.0 / 60.0;
  input.gravity = Vec3(0, -kGravity, 0);
  input.tasks = tasks.get();
  input.colliders = {FluidCollider{1, 1, &obstacle, nullptr, false}};

  const double start = mechanicalEnergy(actor->grid(), actor->levelSet(), solid);
  const int steps = 240, lastSecond = 60;
  double lateEnergy = 0.0, lateSpeed = 0.0;
  for (int s = 0; s < steps; ++s) {
    ActorStats stats;
    actor->step(input, &stats, nullptr);
    ASSERT_FALSE(stats.diverged) << "step " << s;
    if (s < steps - lastSecond) continue;
    lateEnergy = std::max(lateEnergy, mechanicalEnergy(actor->grid(), actor->levelSet(), solid));
    lateSpeed = std::max(lateSpeed, testutil::maxLiquidFaceSpeed(actor->grid(), actor->levelSet()));
  }
  // Nothing in the tank moves faster than free fall from the column's top would make it.
  const double freeFall = std::sqrt(2.0 * kGravity * 2.0 * column.halfExtents.y());
  std::printf("dam break %d^3: mechanical energy %.1f J at the start, at most %.1f J over the last second; fastest "
              "liquid face then %.2f m/s (free fall from the top %.2f m/s)\n",
              n, start, lateEnergy, lateSpeed, freeFall);
  EXPECT_LT(lateEnergy, start);
  EXPECT_LT(lateSpeed, freeFall);
}

}  // namespace
}  // namespace vp

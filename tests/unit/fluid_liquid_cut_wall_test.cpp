// A liquid against a collider wall that cuts its cells behaves like one against a wall on grid
// faces: a dam break hits a box whose front, back and top cut their cells at a sweep of depths,
// and the fastest liquid face of the run must stay near the run with the box on grid faces.
//
// What this guards: a cut cell is open through a whole face, so liquid flows in; if its level
// set is overwritten from its neighbours (level_set_solid_extension.h) its surface cannot rise
// with that inflow, and the projection drains the inflow up the thin cut column through a
// surface that never moves, as a jet many times the flow's speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "collide/face_coverage.h"
#include "fluid/fluid_actor.h"
#include "fluid_liquid_test_util.h"

namespace vp {
namespace {

constexpr int kNx = 32, kNy = 24, kNz = 4;  // a slab: the flow is two-dimensional, and cheap
constexpr double kH = 1.0 / kNx;

// The box's front, back and top faces lie `cut` of a cell past the grid faces at i = 18,
// i = 23 and j = 8; it spans the slab in z.
double fastestLiquidFace(double cut) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  FluidDesc d;
  d.kind = FluidKind::Liquid;
  d.grid.h = kH;
  d.grid.nx = kNx, d.grid.ny = kNy, d.grid.nz = kNz;
  FluidShape column;
  column.type = FluidShape::Type::Box;
  column.halfExtents = Vec3(6 * kH, 9 * kH, 1.0);
  column.centre = Vec3(6 * kH, 9 * kH, kNz * kH / 2);
  d.initialLiquid.push_back(column);
  std::unique_ptr<FluidActor> actor;
  if (FluidActor::create(d, *tasks, &actor) != Status::Ok) return -1.0;
  const double front = (18 + cut) * kH, back = (23 + cut) * kH, top = (8 + cut) * kH;
  ColliderShape box;
  box.kind = ShapeKind::Box;
  box.halfExtents = Vec3((back - front) / 2, top, 1.0);
  box.translation = Vec3((front + back) / 2, 0.0, kNz * kH / 2);
  PreparedCollider prepared;
  if (prepareCollider(box, &prepared) != Status::Ok) return -1.0;
  FluidStepInput input;
  input.dt = 1.0 / 60.0;
  input.gravity = Vec3(0, -9.81, 0);
  input.tasks = tasks.get();
  input.colliders = {FluidCollider{1, 1, &prepared, nullptr, false, {}}};
  double fastest = 0.0;
  for (int s = 0; s < 60; ++s) {
    ActorStats stats;
    actor->step(input, &stats, nullptr);
    if (stats.diverged) return -1.0;
    fastest = std::max(fastest, testutil::maxLiquidFaceSpeed(actor->grid(), actor->levelSet()));
  }
  return fastest;
}

TEST(FluidLiquidCutWall, AJetUpACutWallIsNoFasterThanUpAWallOnGridFaces) {
  const double aligned = fastestLiquidFace(0.0);
  ASSERT_GT(aligned, 0.0);
  // The cut moves the box's faces by under a cell, and the box is 5 cells wide and 8 high:
  // the flow around it changes by a fraction of the peak, not by a factor.
  const double tolerance = 1.25;
  for (double cut : {0.1, 0.2, 0.3, 0.4, 0.48, 0.6, 0.8}) {
    const double fastest = fastestLiquidFace(cut);
    std::printf("    cut %.2f of a cell: fastest liquid face %.2f m/s (on grid faces %.2f)\n", cut, fastest, aligned);
    EXPECT_GT(fastest, 0.0) << "cut " << cut;
    EXPECT_LE(fastest, tolerance * aligned) << "cut " << cut;
  }
}

}  // namespace
}  // namespace vp

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "geometry_test_files.h"
#include "scene/scene_loader.h"
#include "world.h"

namespace vp {
namespace {

std::unique_ptr<World> makeWorld() {
  std::unique_ptr<World> world;
  EXPECT_EQ(World::create(WorldConfig{}, &world), Status::Ok);
  return world;
}

TEST(SceneLoader, LoadsAValidSceneFile) {
  auto world = makeWorld();
  ASSERT_EQ(loadScene(*world, VP_TEST_DATA_DIR "/scenes/stack.json"), Status::Ok) << lastError();
  EXPECT_EQ(world->colliderCount(), 8u);
  EXPECT_DOUBLE_EQ(world->config().frameBudgetMs, 10.0);
  ColliderHandle h;
  ASSERT_TRUE(world->findCollider("ramp", &h));
  const Collider* ramp = world->collider(h);
  EXPECT_EQ(ramp->desc().shape.type, ShapeType::Box);
  EXPECT_NEAR(ramp->pose().rotation.angularDistance(Quat(Eigen::AngleAxisd(20 * M_PI / 180, Vec3::UnitZ()))), 0.0,
              1e-6);
  ASSERT_TRUE(world->findCollider("spinner", &h));
  EXPECT_EQ(world->collider(h)->bodyType(), BodyType::Kinematic);
  EXPECT_NEAR(world->collider(h)->angularVelocity().y(), 2.0, 1e-12);
  for (int i = 0; i < 30; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
}

TEST(SceneLoader, TriangleMeshFromAFileRelativeToTheScene) {
  const test::TempDir dir;
  dir.write("floor.obj", "v -3 0 -3\nv 3 0 -3\nv -3 0 3\nv 3 0 3\nf 1 3 2\nf 2 3 4\n");
  const std::string scene = dir.write("mesh_scene.json", R"({"colliders": [
      {"name": "floor", "shape": {"type": "triangleMesh", "file": "floor.obj", "scale": [2, 1, 2]}},
      {"bodyType": "dynamic", "shape": {"type": "sphere", "radius": 0.25}, "position": [4, 1, 0]}]})");
  auto world = makeWorld();
  ASSERT_EQ(loadScene(*world, scene), Status::Ok) << lastError();
  ColliderHandle h;
  ASSERT_TRUE(world->findCollider("floor", &h));
  EXPECT_EQ(world->collider(h)->desc().shape.triangles.size(), 2u);
  double maxX = -1e9;  // assimp may reorder vertices; the extent shows the scale
  for (const Vec3& p : world->collider(h)->desc().shape.points) maxX = std::max(maxX, p.x());
  EXPECT_DOUBLE_EQ(maxX, 6.0);
  for (int i = 0; i < 120; ++i) world->step(1.0 / 60.0);
  // The ball at x = 4 lands on the scaled floor (it would fall past the unscaled one).
  auto handles = world->colliderHandles();
  EXPECT_NEAR(world->collider(handles[1])->pose().position.y(), 0.25, 5e-3);
}

struct BadScene {
  const char* json;
  Status status;
  const char* messagePart;
};

class SceneLoaderRejects : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneLoaderRejects, WithThePathAndChangesNothing) {
  const BadScene& bad = GetParam();
  auto world = makeWorld();
  const double budgetBefore = world->config().frameBudgetMs;
  Status s = loadSceneFromString(*world, bad.json, ".");
  EXPECT_EQ(s, bad.status) << lastError();
  EXPECT_NE(std::string(lastError()).find(bad.messagePart), std::string::npos)
      << "message: " << lastError() << "\nexpected to contain: " << bad.messagePart;
  EXPECT_EQ(world->colliderCount(), 0u);
  EXPECT_EQ(world->deformableCount(), 0u);
  EXPECT_EQ(world->fluidCount(), 0u);
  EXPECT_EQ(world->config().frameBudgetMs, budgetBefore);
}

// Every scene below has a valid first collider and a "world" block, so a loader that applied
// anything before failing would be caught by the unchanged-world checks.
#define GOOD_PREFIX R"({"world": {"frameBudgetMs": 3}, "colliders": [{"shape": {"type": "plane"}}, )"

INSTANTIATE_TEST_SUITE_P(
    Malformed, SceneLoaderRejects,
    ::testing::Values(
        BadScene{"{ not json", Status::ParseError, "$: invalid JSON"},
        BadScene{"[1, 2]", Status::ParseError, "$: expected an object"},
        BadScene{R"({"colliderz": []})", Status::ParseError, "$.colliderz: unknown key"},
        BadScene{R"({"version": 2})", Status::ParseError, "$.version = 2"},
        BadScene{R"({"colliders": {}})", Status::ParseError, "$.colliders: expected an array"},
        BadScene{R"({"world": {"gravity": [0, "down", 0]}})", Status::ParseError, "$.world.gravity: expected an array of 3 numbers"},
        BadScene{R"({"world": {"frameBudgetMs": -5}})", Status::InvalidArgument, "$.world: frameBudgetMs = -5"},
        BadScene{R"({"world": {"gravity": [0, 1e9, 0]}})", Status::InvalidArgument, "$.world: gravity"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "sphere", "radius": -1}}]})", Status::InvalidArgument,
                 "$.colliders[1]: shape.radius = -1"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "sphere", "radius": "big"}}]})", Status::ParseError,
                 "$.colliders[1].shape.radius: expected a number, got string"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "sphere", "radiuss": 1}}]})", Status::ParseError,
                 "$.colliders[1].shape.radiuss: unknown key"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "blob"}}]})", Status::ParseError,
                 "$.colliders[1].shape.type = \"blob\": expected one of"},
        BadScene{GOOD_PREFIX R"({"shape": {"radius": 1}}]})", Status::ParseError, "$.colliders[1].shape.type: missing"},
        BadScene{GOOD_PREFIX R"({"bodyType": "floaty", "shape": {"type": "sphere"}}]})", Status::ParseError,
                 "$.colliders[1].bodyType = \"floaty\""},
        BadScene{GOOD_PREFIX R"({"bodyType": "dynamic"}]})", Status::ParseError, "$.colliders[1].shape: missing"},
        BadScene{GOOD_PREFIX R"({"bodyType": "dynamic", "mass": -2, "shape": {"type": "box"}}]})",
                 Status::InvalidArgument, "$.colliders[1]: mass = -2"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "box"}, "rotation": [0, 0, 0]}]})", Status::ParseError,
                 "$.colliders[1].rotation: expected a quaternion"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "box"}, "rotation": [0, 0, 0, 3]}]})", Status::InvalidArgument,
                 "$.colliders[1]: pose.rotation"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "box"}, "axisAngle": [0, 0, 0, 30]}]})", Status::ParseError,
                 "$.colliders[1].axisAngle: the axis must be"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "convexHull", "points": [[0, 0, 0], [1, 0]]}}]})",
                 Status::ParseError, "$.colliders[1].shape.points[1]: expected [x, y, z]"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "triangleMesh", "points": [[0,0,0],[1,0,0],[0,0,1]], "triangles": [[0, 1, 5]]}}]})",
                 Status::InvalidArgument, "$.colliders[1]: shape.indices[2] = 5"},
        BadScene{GOOD_PREFIX R"({"shape": {"type": "triangleMesh", "file": "missing.obj"}}]})", Status::IoError,
                 "$.colliders[1]: shape.meshFile: file './missing.obj': cannot be opened"},
        BadScene{GOOD_PREFIX R"(7]})", Status::ParseError, "$.colliders[1]: expected an object, got number"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"box": {}, "stiff": 1}]})",
                 Status::ParseError, "$.deformables[0].stiff: unknown key"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"box": {"cells": [2, 0, 2]}}]})",
                 Status::ParseError, "$.deformables[0].box.cells: expected 3 integers"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{}]})", Status::InvalidArgument,
                 "$.deformables[0]: mesh source: give exactly one of"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"box": {}, "youngsModulus": -1}]})",
                 Status::InvalidArgument, "$.deformables[0]: youngsModulus = -1"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"box": {}, "targetResidual": 0}]})",
                 Status::InvalidArgument, "$.deformables[0]: targetResidual = 0: must be >= solverTolerance = 0.001"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}],
                     "deformables": [{"box": {}, "solverTolerance": 0.05, "targetResidual": 0.02}]})",
                 Status::InvalidArgument, "$.deformables[0]: targetResidual = 0.02: must be >= solverTolerance = 0.05"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"box": {}, "targetResidual": 1.5}]})",
                 Status::InvalidArgument,
                 "$.deformables[0]: targetResidual = 1.5: must be finite and in [solverTolerance, 1]"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"box": {}, "targetResidual": "low"}]})",
                 Status::ParseError, "$.deformables[0].targetResidual: expected a number, got string"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"box": {}, "priority": 1000001}]})",
                 Status::InvalidArgument, "$.deformables[0]: priority = 1000001: must be in [-1000000, 1000000]"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"box": {}, "priority": 2.5}]})",
                 Status::ParseError, "$.deformables[0].priority: expected an integer, got 2.5"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "deformables": [{"tetFile": "none.msh"}]})",
                 Status::IoError, "$.deformables[0]: tetFile"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}],
                     "deformables": [{"box": {}, "pinBox": {"min": [5, 5, 5], "max": [6, 6, 6]}}]})",
                 Status::ParseError, "$.deformables[0].pinBox: selects no node"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}],
                     "deformables": [{"box": {}, "attach": [{"collider": "ghost", "box": {"min": [-1, -1, -1], "max": [1, 1, 1]}}]}]})",
                 Status::ParseError, "$.deformables[0].attach[0].collider = \"ghost\": no collider"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"kind": "lava"}]})", Status::ParseError,
                 "$.fluids[0].kind = \"lava\": expected one of"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"resolution": [8, 1, 8]}]})",
                 Status::ParseError, "$.fluids[0].resolution: expected 3 integers in [2, 1024]"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"cellSize": 0}]})",
                 Status::InvalidArgument, "$.fluids[0]: cellSize = 0"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"kinematicViscosity": -2}]})",
                 Status::InvalidArgument, "$.fluids[0]: kinematicViscosity = -2: must be in [0, 10]"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"priority": -1000001}]})",
                 Status::InvalidArgument, "$.fluids[0]: priority = -1000001: must be in [-1000000, 1000000]"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"priority": 10000000000}]})",
                 Status::ParseError, "$.fluids[0].priority = 10000000000: out of the integer range"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"sides": {"+y": "door"}}]})",
                 Status::ParseError, "$.fluids[0].sides.+y = \"door\": expected one of"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}],
                     "fluids": [{"emitters": [{"region": {"type": "sphere", "radius": -1}}]}]})",
                 Status::InvalidArgument, "$.fluids[0]: emitters[0].region.radius = -1"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"emitters": [{"velocity": [0, 1, 0]}]}]})",
                 Status::ParseError, "$.fluids[0].emitters[0].region: missing"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}}], "fluids": [{"smoke": {"heat": 1}}]})",
                 Status::ParseError, "$.fluids[0].smoke.heat: unknown key"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}, "collisionFilter": {"category": -1}}]})",
                 Status::ParseError, "$.colliders[0].collisionFilter.category = -1: expected an integer in [0, 4294967295]"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}, "collisionFilter": {"mask": 4294967296}}]})",
                 Status::ParseError, "$.colliders[0].collisionFilter.mask = 4294967296: expected an integer"},
        BadScene{R"({"deformables": [{"box": {}, "collisionFilter": {"mask": 1.5}}]})", Status::ParseError,
                 "$.deformables[0].collisionFilter.mask = 1.5: expected an integer"},
        BadScene{R"({"fluids": [{"collisionFilter": {"group": 1}}]})", Status::ParseError,
                 "$.fluids[0].collisionFilter.group: unknown key"},
        BadScene{R"({"fluids": [{"collisionFilter": 3}]})", Status::ParseError, "$.fluids[0].collisionFilter"},
        BadScene{R"({"colliders": [{"shape": {"type": "plane"}, "sleeping": true}]})", Status::InvalidArgument,
                 "$.colliders[0]: sleeping: only a dynamic body sleeps"},
        BadScene{R"({"colliders": [{"bodyType": "dynamic", "shape": {"type": "sphere", "radius": 1}, "sleeping": 1}]})",
                 Status::ParseError, "$.colliders[0].sleeping"}));

TEST(SceneLoader, DeformableWithPinsAndAnAttachment) {
  auto world = makeWorld();
  ASSERT_EQ(loadScene(*world, VP_TEST_DATA_DIR "/scenes/jelly_bridge.json"), Status::Ok) << lastError();
  world->setFrameBudget(0.0);  // physics checked below must not depend on the machine's speed
  ASSERT_EQ(world->deformableCount(), 1u);
  DeformableHandle h;
  ASSERT_TRUE(world->findDeformable("bridge", &h));
  DeformableBody* bridge = world->deformable(h);
  EXPECT_EQ(bridge->nodeCount(), 9 * 3 * 3);
  EXPECT_EQ(bridge->attachmentCount(), 9);
  int pinned = 0;
  for (int32_t i = 0; i < bridge->nodeCount(); ++i) pinned += bridge->pinned(i);
  EXPECT_EQ(pinned, 9);
  EXPECT_DOUBLE_EQ(bridge->desc().material.youngsModulus, 2e5);
  for (int i = 0; i < 60; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  // Held at both ends, the bridge sags in the middle but stays up.
  double minY = 1e9;
  for (int32_t i = 0; i < bridge->nodeCount(); ++i) minY = std::min(minY, bridge->positions()[3 * i + 1]);
  EXPECT_LT(minY, 1.0 - 0.125 - 1e-3);
  EXPECT_GT(minY, 0.0);
}

TEST(SceneLoader, ReadsTheAccuracyFloorAndPriorities) {
  auto world = makeWorld();
  ASSERT_EQ(loadSceneFromString(*world, R"({
      "deformables": [{"name": "jelly", "box": {"cells": [1, 1, 1], "size": [1, 1, 1]},
                       "solverTolerance": 0.002, "targetResidual": 0.05, "priority": 12},
                      {"name": "plain", "box": {"cells": [1, 1, 1], "size": [1, 1, 1]}, "position": [3, 0, 0]}],
      "fluids": [{"name": "tank", "resolution": [4, 4, 4], "priority": -7}]})", "."),
            Status::Ok)
      << lastError();
  DeformableHandle jelly, plain;
  ASSERT_TRUE(world->findDeformable("jelly", &jelly));
  ASSERT_TRUE(world->findDeformable("plain", &plain));
  EXPECT_DOUBLE_EQ(world->deformable(jelly)->desc().solver.targetResidual, 0.05);
  EXPECT_EQ(world->deformable(jelly)->desc().priority, 12);
  // Keys left out keep the C ABI's defaults.
  EXPECT_DOUBLE_EQ(world->deformable(plain)->desc().solver.targetResidual, 1e-2);
  EXPECT_EQ(world->deformable(plain)->desc().priority, 0);
  FluidHandle tank;
  ASSERT_TRUE(world->findFluid("tank", &tank));
  EXPECT_EQ(world->fluid(tank)->desc().priority, -7);
}

// "startAtRest": the jelly is solved onto the ground under the scene's own gravity before the
// first step; one with nothing under it has no equilibrium, and the load fails as a whole.
TEST(SceneLoader, StartAtRestSettlesAJellyOnTheGroundOrFailsTheWholeLoad) {
  auto world = makeWorld();
  ASSERT_EQ(loadSceneFromString(*world, R"({"world": {"gravity": [0, -5, 0]},
      "colliders": [{"name": "ground", "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}}],
      "deformables": [{"name": "jelly", "degree": 2, "box": {"cells": [2, 2, 2], "size": [0.4, 0.4, 0.4]},
                       "position": [0, 0.3, 0], "youngsModulus": 1e5, "startAtRest": true},
                      {"name": "held", "box": {"cells": [1, 1, 1], "size": [0.4, 0.4, 0.4]},
                       "position": [2, 1, 0]}]})",
                                "."),
            Status::Ok)
      << lastError();
  DeformableHandle jelly, held;
  ASSERT_TRUE(world->findDeformable("jelly", &jelly));
  ASSERT_TRUE(world->findDeformable("held", &held));
  const DeformableBody& body = *world->deformable(jelly);
  double lowest = 1e9;
  for (int32_t i = 0; i < body.nodeCount(); ++i) lowest = std::min(lowest, body.positions()[3 * i + 1]);
  EXPECT_GE(lowest, -1e-6);
  EXPECT_LT(lowest, 0.01);
  for (double v : body.velocities()) EXPECT_EQ(v, 0.0);
  // The other one was not asked to: it is where the file put it.
  EXPECT_DOUBLE_EQ(world->deformable(held)->positions()[1], 0.8);

  auto empty = makeWorld();
  const Vec3 gravity = empty->gravity();
  EXPECT_EQ(loadSceneFromString(*empty, R"({"world": {"gravity": [0, -5, 0]},
      "deformables": [{"box": {"cells": [1, 1, 1], "size": [0.4, 0.4, 0.4]}, "startAtRest": true}]})",
                                "."),
            Status::NotConverged);
  EXPECT_NE(std::string(lastError()).find("$.deformables[0].startAtRest"), std::string::npos) << lastError();
  EXPECT_EQ(empty->deformableCount(), 0u);
  EXPECT_EQ(empty->gravity(), gravity);
  EXPECT_EQ(loadSceneFromString(*empty, R"({"deformables": [{"box": {"cells": [1, 1, 1], "size": [1, 1, 1]},
                                                              "startAtRest": 1}]})",
                                "."),
            Status::ParseError);
  EXPECT_NE(std::string(lastError()).find("startAtRest"), std::string::npos) << lastError();
}

// A body that starts asleep hangs where it was put until something wakes it; one left awake
// falls.
TEST(SceneLoader, ASleepingBodyStaysPutUntilWoken) {
  auto world = makeWorld();
  ASSERT_EQ(loadSceneFromString(*world, R"({"colliders": [
      {"name": "asleep", "bodyType": "dynamic", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 5, 0],
       "sleeping": true},
      {"name": "awake", "bodyType": "dynamic", "shape": {"type": "sphere", "radius": 0.5}, "position": [3, 5, 0],
       "sleeping": false}]})", "."),
            Status::Ok)
      << lastError();
  world->setFrameBudget(0.0);
  ColliderHandle asleep, awake;
  ASSERT_TRUE(world->findCollider("asleep", &asleep));
  ASSERT_TRUE(world->findCollider("awake", &awake));
  EXPECT_TRUE(world->collider(asleep)->sleeping());
  EXPECT_FALSE(world->collider(awake)->sleeping());
  for (int i = 0; i < 30; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  EXPECT_EQ(world->collider(asleep)->pose().position.y(), 5.0);
  EXPECT_LT(world->collider(awake)->pose().position.y(), 4.0);
  world->collider(asleep)->setSleeping(false);
  for (int i = 0; i < 30; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  EXPECT_LT(world->collider(asleep)->pose().position.y(), 4.0);
}

TEST(SceneLoader, ReadsCollisionFiltersAndKeepsTheDefaultsOfKeysLeftOut) {
  auto world = makeWorld();
  ASSERT_EQ(loadSceneFromString(*world, R"({
      "colliders": [{"name": "floor", "shape": {"type": "plane"}, "collisionFilter": {"category": 4294967295, "mask": 6}},
                    {"name": "wall", "shape": {"type": "box", "halfExtents": [1, 1, 1]}, "collisionFilter": {"mask": 0}}],
      "deformables": [{"name": "jelly", "box": {"cells": [1, 1, 1], "size": [1, 1, 1]}, "position": [0, 3, 0],
                       "collisionFilter": {"category": 2}}],
      "fluids": [{"name": "tank", "resolution": [4, 4, 4], "collisionFilter": {"category": 8, "mask": 1}}]})", "."),
            Status::Ok)
      << lastError();
  ColliderHandle floor, wall;
  ASSERT_TRUE(world->findCollider("floor", &floor));
  ASSERT_TRUE(world->findCollider("wall", &wall));
  EXPECT_EQ(world->collider(floor)->filter().category, 0xFFFFFFFFu);
  EXPECT_EQ(world->collider(floor)->filter().mask, 6u);
  EXPECT_EQ(world->collider(wall)->filter().category, 1u);
  EXPECT_EQ(world->collider(wall)->filter().mask, 0u);
  DeformableHandle jelly;
  ASSERT_TRUE(world->findDeformable("jelly", &jelly));
  EXPECT_EQ(world->deformable(jelly)->desc().filter.category, 2u);
  EXPECT_EQ(world->deformable(jelly)->desc().filter.mask, 0xFFFFFFFFu);
  FluidHandle tank;
  ASSERT_TRUE(world->findFluid("tank", &tank));
  EXPECT_EQ(world->fluid(tank)->desc().filter.category, 8u);
  EXPECT_EQ(world->fluid(tank)->desc().filter.mask, 1u);
}

// A closed unit cube as an OBJ surface, and a scene with one deformable whose extra keys are
// `deformable` (JSON text without braces), in a folder of this test's own: in the shared
// temporary folder, test processes running at the same time rewrote each other's cube while
// the loader read it.
std::string writeCubeScene(const test::TempDir& dir, const std::string& name, const std::string& deformable) {
  dir.write("unit_cube.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
            "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\n"
            "f 2 3 7\nf 2 7 6\n");
  return dir.write(name, std::string(R"({"deformables": [{"name": "jelly", )") + deformable + "}]}");
}

// Loads a cube scene (writeCubeScene) into a new world and copies the jelly's tets to `mesh`.
Status loadCubeSceneMesh(const test::TempDir& dir, const std::string& name, const std::string& deformable,
                         TetMesh* mesh) {
  auto world = makeWorld();
  const Status s = loadScene(*world, writeCubeScene(dir, name, deformable));
  DeformableHandle h;
  if (ok(s) && world->findDeformable("jelly", &h)) *mesh = world->deformable(h)->desc().mesh;
  return s;
}

double extentX(const DeformableBody& body) {
  double lo = 1e9, hi = -1e9;
  for (int32_t i = 0; i < body.nodeCount(); ++i) {
    lo = std::min(lo, body.positions()[3 * i]);
    hi = std::max(hi, body.positions()[3 * i]);
  }
  return hi - lo;
}

TEST(SceneLoader, DeformableScaleAppliesToTheSurfaceFile) {
  const test::TempDir dir;
  auto world = makeWorld();
  const std::string path = writeCubeScene(dir, "scaled_cube.json", R"("surfaceFile": "unit_cube.obj", "scale": 0.5)");
  ASSERT_EQ(loadScene(*world, path), Status::Ok) << lastError();
  DeformableHandle h;
  ASSERT_TRUE(world->findDeformable("jelly", &h));
  EXPECT_NEAR(extentX(*world->deformable(h)), 0.5, 1e-9);
}

// "surfaceMesher": "stuffing" (the default) or "voxel"; voxelResolution applies to either.
TEST(SceneLoader, SurfaceMesherChoosesHowTheSurfaceFileBecomesTets) {
  const test::TempDir dir;
  auto load = [&](const std::string& name, const std::string& keys, TetMesh* mesh) {
    return loadCubeSceneMesh(dir, name, R"("surfaceFile": "unit_cube.obj", "voxelResolution": 4)" + keys, mesh);
  };
  TetMesh voxel, stuffed, byDefault;
  ASSERT_EQ(load("voxel.json", R"(, "surfaceMesher": "voxel")", &voxel), Status::Ok) << lastError();
  ASSERT_EQ(load("stuffing.json", R"(, "surfaceMesher": "stuffing")", &stuffed), Status::Ok) << lastError();
  ASSERT_EQ(load("default.json", "", &byDefault), Status::Ok) << lastError();
  EXPECT_EQ(voxel.vertices.size(), 125u);  // the 4 x 4 x 4 cells' corners
  EXPECT_EQ(voxel.tets.size(), 6u * 64u);
  EXPECT_EQ(byDefault.tets, stuffed.tets);
  EXPECT_NE(stuffed.tets.size(), voxel.tets.size());
  EXPECT_NEAR(totalVolume(stuffed), 1.0, 1e-12);
  TetMesh unused;
  EXPECT_EQ(load("octree.json", R"(, "surfaceMesher": "octree")", &unused), Status::ParseError);
  EXPECT_NE(std::string(lastError()).find(
                R"($.deformables[0].surfaceMesher = "octree": expected one of: stuffing, voxel)"),
            std::string::npos)
      << lastError();
}

// "meshGrading": levels of coarsening inside for stuffing, 0 (the default) the uniform lattice;
// out of range it is refused naming the field and value.
TEST(SceneLoader, MeshGradingReachesTheMesher) {
  const test::TempDir dir;
  auto load = [&](const std::string& name, const std::string& keys, TetMesh* mesh) {
    return loadCubeSceneMesh(dir, name, R"("surfaceFile": "unit_cube.obj", "voxelResolution": 24)" + keys, mesh);
  };
  TetMesh uniform, zero, graded, unused;
  ASSERT_EQ(load("uniform.json", "", &uniform), Status::Ok) << lastError();
  ASSERT_EQ(load("zero.json", R"(, "meshGrading": 0)", &zero), Status::Ok) << lastError();
  ASSERT_EQ(load("graded.json", R"(, "meshGrading": 2)", &graded), Status::Ok) << lastError();
  EXPECT_EQ(zero.tets, uniform.tets);
  EXPECT_LT(graded.tets.size(), uniform.tets.size());
  EXPECT_NEAR(totalVolume(graded), 1.0, 1e-9);
  EXPECT_EQ(load("bad.json", R"(, "meshGrading": 9)", &unused), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("meshGrading = 9"), std::string::npos) << lastError();
}

// "selfCollision": "auto" (the default), "off" or "on"; anything else is refused naming it.
TEST(SceneLoader, SelfCollisionIsAutoOffOrOn) {
  const test::TempDir dir;
  auto load = [&](const std::string& name, const std::string& keys, SelfCollision* self) {
    auto world = makeWorld();
    const Status s = loadScene(*world, writeCubeScene(dir, name, R"("box": {"cells": [2, 2, 2], "size": [1, 1, 1]})" + keys));
    DeformableHandle h;
    if (ok(s) && world->findDeformable("jelly", &h)) *self = world->deformable(h)->desc().selfCollision;
    return s;
  };
  SelfCollision self = SelfCollision::On;
  ASSERT_EQ(load("default.json", "", &self), Status::Ok) << lastError();
  EXPECT_EQ(self, SelfCollision::Auto);
  ASSERT_EQ(load("off.json", R"(, "selfCollision": "off")", &self), Status::Ok) << lastError();
  EXPECT_EQ(self, SelfCollision::Off);
  ASSERT_EQ(load("on.json", R"(, "selfCollision": "on")", &self), Status::Ok) << lastError();
  EXPECT_EQ(self, SelfCollision::On);
  EXPECT_EQ(load("bad.json", R"(, "selfCollision": "sometimes")", &self), Status::ParseError);
  EXPECT_NE(std::string(lastError()).find(
                R"($.deformables[0].selfCollision = "sometimes": expected one of: auto, off, on)"),
            std::string::npos)
      << lastError();
}

TEST(SceneLoader, IfFileMissingStandsInOnlyWhenTheFileIsAbsent) {
  const test::TempDir dir;
  const char* fallback = R"("ifFileMissing": {"box": {"cells": [2, 1, 1], "size": [3, 1, 1]}}, "density": 500)";
  {
    auto world = makeWorld();  // the file is there: the fallback is ignored
    const std::string path =
        writeCubeScene(dir, "present.json", std::string(R"("surfaceFile": "unit_cube.obj", )") + fallback);
    ASSERT_EQ(loadScene(*world, path), Status::Ok) << lastError();
    DeformableHandle h;
    ASSERT_TRUE(world->findDeformable("jelly", &h));
    EXPECT_NEAR(extentX(*world->deformable(h)), 1.0, 1e-9);
  }
  {
    auto world = makeWorld();  // the file is absent: the box, with the other keys kept
    const std::string path = writeCubeScene(dir,
        "absent.json", std::string(R"("surfaceFile": "/no/such/duck.dae", "scale": 9, )") + fallback);
    ASSERT_EQ(loadScene(*world, path), Status::Ok) << lastError();
    DeformableHandle h;
    ASSERT_TRUE(world->findDeformable("jelly", &h));
    const DeformableBody& body = *world->deformable(h);
    EXPECT_EQ(body.nodeCount(), 3 * 2 * 2);
    EXPECT_NEAR(extentX(body), 3.0, 1e-9);  // the file's scale went with the file
    EXPECT_DOUBLE_EQ(body.desc().material.density, 500);
  }
  {
    auto world = makeWorld();
    const std::string path = writeCubeScene(dir, "no_file.json", R"("box": {"cells": [1, 1, 1], "size": [1, 1, 1]},
                                            "ifFileMissing": {"box": {"cells": [1, 1, 1], "size": [1, 1, 1]}})");
    EXPECT_EQ(loadScene(*world, path), Status::ParseError);
    EXPECT_NE(std::string(lastError()).find("$.deformables[0].ifFileMissing: needs a surfaceFile or tetFile"),
              std::string::npos)
        << lastError();
    EXPECT_EQ(world->deformableCount(), 0u);
  }
}

TEST(SceneLoader, MissingFileIsAnIoError) {
  auto world = makeWorld();
  EXPECT_EQ(loadScene(*world, "/does/not/exist.json"), Status::IoError);
  EXPECT_NE(std::string(lastError()).find("/does/not/exist.json"), std::string::npos);
}

}  // namespace
}  // namespace vp

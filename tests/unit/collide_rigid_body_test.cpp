// Rigid colliders through the runtime World (Bullet underneath).
#include <gtest/gtest.h>

#include <cmath>

#include "world.h"

namespace vp {
namespace {

std::unique_ptr<World> makeWorld(int workers = 1) {
  WorldConfig config;
  config.workerCount = workers;
  std::unique_ptr<World> world;
  EXPECT_EQ(World::create(config, &world), Status::Ok) << lastError();
  return world;
}

ColliderHandle addGround(World& world) {
  ColliderDesc ground;
  ground.shape.type = ShapeType::Plane;
  ColliderHandle h;
  EXPECT_EQ(world.createCollider(ground, &h), Status::Ok) << lastError();
  return h;
}

TEST(RigidBody, BoxDroppedOnPlaneRestsAtItsHalfHeight) {
  auto world = makeWorld();
  addGround(*world);
  ColliderDesc box;
  box.bodyType = BodyType::Dynamic;
  box.shape.type = ShapeType::Box;
  box.shape.halfExtents = Vec3(0.4, 0.25, 0.3);
  box.pose.position = Vec3(0.0, 2.0, 0.0);
  ColliderHandle h;
  ASSERT_EQ(world->createCollider(box, &h), Status::Ok) << lastError();
  for (int i = 0; i < 240; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  const Pose p = world->collider(h)->pose();
  // Bullet resolves contacts to within its contact margin (0.04 m by default for boxes,
  // held inside the shape) and a small allowed penetration; 5 mm is well inside that.
  EXPECT_NEAR(p.position.y(), 0.25, 5e-3);
  // Bullet's sequential-impulse solver treats the four landing corners one after another, so
  // a flat landing slides a little sideways; a few centimetres, never a topple.
  EXPECT_NEAR(p.position.x(), 0.0, 0.05);
  EXPECT_NEAR(p.position.z(), 0.0, 0.05);
  EXPECT_LT(world->collider(h)->linearVelocity().norm(), 1e-2);
  // Still upright: the local Y axis points up.
  EXPECT_GT((p.rotation * Vec3::UnitY()).y(), 0.999);
}

TEST(RigidBody, FreeFallMatchesBallisticMotionBeforeContact) {
  auto world = makeWorld();
  ColliderDesc ball;
  ball.bodyType = BodyType::Dynamic;
  ball.angularDamping = 0.0;
  ball.pose.position = Vec3(0, 10, 0);
  ColliderHandle h;
  ASSERT_EQ(world->createCollider(ball, &h), Status::Ok);
  const int steps = 30;
  for (int i = 0; i < steps; ++i) world->step(1.0 / 60.0);
  // Bullet integrates semi-implicit Euler per 1/120 s sub-step: y = y0 - g h^2 n(n+1)/2.
  const double h2 = 1.0 / 120.0, n = 2.0 * steps;
  const double expected = 10.0 - 9.81 * h2 * h2 * n * (n + 1) / 2.0;
  EXPECT_NEAR(world->collider(h)->pose().position.y(), expected, 1e-4);  // float storage
  EXPECT_EQ(world->lastStats().rigidSubsteps, 2);
}

TEST(RigidBody, KinematicBodyReachesItsTargetAndFollowsIt) {
  auto world = makeWorld();
  ColliderDesc paddle;
  paddle.bodyType = BodyType::Kinematic;
  paddle.shape.type = ShapeType::Box;
  ColliderHandle h;
  ASSERT_EQ(world->createCollider(paddle, &h), Status::Ok);
  Collider* c = world->collider(h);
  const double dt = 1.0 / 60.0;
  for (int i = 1; i <= 60; ++i) {
    const double t = i * dt;
    Pose target;
    target.position = Vec3(std::sin(t), 0.5 * t, 0.0);
    target.rotation = Quat(Eigen::AngleAxisd(0.8 * t, Vec3::UnitY()));
    c->setKinematicTarget(target);
    ASSERT_EQ(world->step(dt), Status::Ok);
    EXPECT_LT((c->pose().position - target.position).norm(), 1e-12);
    EXPECT_LT(c->pose().rotation.angularDistance(target.rotation), 1e-9);
    // The velocity Bullet's contacts (and later fluids) see is the one that reaches the target.
    EXPECT_NEAR(c->angularVelocity().y(), 0.8, 1e-6);
  }
  // With no new target the body stops where it is.
  const Vec3 last = c->pose().position;
  world->step(dt);
  world->step(dt);
  EXPECT_LT((c->pose().position - last).norm(), 1e-12);
  EXPECT_LT(c->linearVelocity().norm(), 1e-12);
}

TEST(RigidBody, KinematicBodyWithVelocityPushesADynamicBox) {
  auto world = makeWorld();
  addGround(*world);
  ColliderDesc pusher;
  pusher.bodyType = BodyType::Kinematic;
  pusher.shape.type = ShapeType::Box;
  pusher.shape.halfExtents = Vec3(0.1, 0.5, 1.0);
  pusher.pose.position = Vec3(-1.0, 0.5, 0.0);
  pusher.linearVelocity = Vec3(1.0, 0.0, 0.0);
  ColliderDesc box;
  box.bodyType = BodyType::Dynamic;
  box.shape.type = ShapeType::Box;
  box.shape.halfExtents = Vec3(0.25, 0.25, 0.25);
  box.pose.position = Vec3(0.0, 0.25, 0.0);
  ColliderHandle hp, hb;
  ASSERT_EQ(world->createCollider(pusher, &hp), Status::Ok);
  ASSERT_EQ(world->createCollider(box, &hb), Status::Ok);
  for (int i = 0; i < 120; ++i) world->step(1.0 / 60.0);
  // After 2 s the pusher's face is at x = 1.1; the box sits in front of it.
  const double pusherX = world->collider(hp)->pose().position.x();
  EXPECT_NEAR(pusherX, 1.0, 1e-6);
  EXPECT_NEAR(world->collider(hb)->pose().position.x(), pusherX + 0.1 + 0.25, 0.05);
}

TEST(RigidBody, EveryShapeTypeCanBeCreated) {
  auto world = makeWorld();
  std::vector<ColliderDesc> descs(7);
  descs[0].shape.type = ShapeType::Sphere;
  descs[1].shape.type = ShapeType::Box;
  descs[2].shape.type = ShapeType::Capsule;
  descs[3].shape.type = ShapeType::Cylinder;
  descs[4].shape.type = ShapeType::Plane;
  descs[5].shape.type = ShapeType::ConvexHull;
  descs[5].shape.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  descs[6].shape.type = ShapeType::TriangleMesh;
  descs[6].shape.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1)};
  descs[6].shape.triangles = {{0, 2, 1}, {1, 2, 3}};
  for (auto& d : descs) {
    ColliderHandle h;
    EXPECT_EQ(world->createCollider(d, &h), Status::Ok) << shapeTypeName(d.shape.type) << ": " << lastError();
  }
  EXPECT_EQ(world->colliderCount(), 7u);
  EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok);
}

TEST(RigidBody, TriangleMeshFloorHoldsASphere) {
  auto world = makeWorld();
  ColliderDesc floor;
  floor.shape.type = ShapeType::TriangleMesh;
  floor.shape.points = {Vec3(-5, 0, -5), Vec3(5, 0, -5), Vec3(-5, 0, 5), Vec3(5, 0, 5)};
  floor.shape.triangles = {{0, 2, 1}, {1, 2, 3}};
  ColliderDesc ball;
  ball.bodyType = BodyType::Dynamic;
  ball.shape.radius = 0.3;
  ball.pose.position = Vec3(0.2, 1.0, 0.1);
  ColliderHandle hf, hb;
  ASSERT_EQ(world->createCollider(floor, &hf), Status::Ok);
  ASSERT_EQ(world->createCollider(ball, &hb), Status::Ok);
  for (int i = 0; i < 180; ++i) world->step(1.0 / 60.0);
  EXPECT_NEAR(world->collider(hb)->pose().position.y(), 0.3, 5e-3);
}

TEST(RigidBody, InvalidDescsAreRejectedWithTheFieldNameAndChangeNothing) {
  auto world = makeWorld();
  struct Case {
    const char* expected;
    void (*mutate)(ColliderDesc&);
  } cases[] = {
      {"shape.radius", [](ColliderDesc& d) { d.shape.radius = -1.0; }},
      {"shape.radius", [](ColliderDesc& d) { d.shape.radius = std::nan(""); }},
      {"shape.halfExtents.y", [](ColliderDesc& d) { d.shape.type = ShapeType::Box; d.shape.halfExtents.y() = 0; }},
      {"pose.position", [](ColliderDesc& d) { d.pose.position.x() = INFINITY; }},
      {"pose.rotation", [](ColliderDesc& d) { d.pose.rotation = Quat(2, 0, 0, 0); }},
      {"mass", [](ColliderDesc& d) { d.bodyType = BodyType::Dynamic; d.mass = 0.0; }},
      {"friction", [](ColliderDesc& d) { d.friction = -0.1; }},
      {"restitution", [](ColliderDesc& d) { d.restitution = 1.5; }},
      {"bodyType", [](ColliderDesc& d) { d.bodyType = static_cast<BodyType>(7); }},
      {"shape.type", [](ColliderDesc& d) { d.shape.type = static_cast<ShapeType>(-1); }},
      {"plane", [](ColliderDesc& d) { d.bodyType = BodyType::Dynamic; d.shape.type = ShapeType::Plane; }},
      {"coplanar", [](ColliderDesc& d) {
         d.shape.type = ShapeType::ConvexHull;
         d.shape.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
       }},
      {"shape.indices[4]", [](ColliderDesc& d) {
         d.shape.type = ShapeType::TriangleMesh;
         d.shape.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)};
         d.shape.triangles = {{0, 1, 2}, {0, 9, 2}};
       }},
      {"shape.meshFile", [](ColliderDesc& d) { d.shape.type = ShapeType::TriangleMesh; d.shape.meshFile = "/nope.obj"; }},
      {"a static body cannot move", [](ColliderDesc& d) { d.linearVelocity = Vec3(1, 0, 0); }},
  };
  for (const Case& c : cases) {
    ColliderDesc desc;
    c.mutate(desc);
    ColliderHandle h;
    Status s = world->createCollider(desc, &h);
    EXPECT_NE(s, Status::Ok) << c.expected;
    EXPECT_NE(std::string(lastError()).find(c.expected), std::string::npos)
        << "message '" << lastError() << "' should mention '" << c.expected << "'";
  }
  EXPECT_EQ(world->colliderCount(), 0u);
}

TEST(RigidBody, DestroyedColliderLeavesTheSimulation) {
  auto world = makeWorld();
  ColliderHandle ground = addGround(*world);
  ColliderDesc ball;
  ball.bodyType = BodyType::Dynamic;
  ball.pose.position = Vec3(0, 1, 0);
  ColliderHandle hb;
  ASSERT_EQ(world->createCollider(ball, &hb), Status::Ok);
  ASSERT_EQ(world->destroyCollider(ground), Status::Ok);
  EXPECT_EQ(world->destroyCollider(ground), Status::InvalidId);
  for (int i = 0; i < 60; ++i) world->step(1.0 / 60.0);
  EXPECT_LT(world->collider(hb)->pose().position.y(), -2.0);  // fell through where the ground was
}

}  // namespace
}  // namespace vp

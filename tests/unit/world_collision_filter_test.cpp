// Collision filtering (core/collision_filter.h) in each place it applies: rigid pairs in Bullet,
// a deformable's contacts, a fluid's face fractions; and changes after creation.
#include <gtest/gtest.h>

#include "geometry/box_tet_mesh.h"
#include "world.h"

namespace vp {
namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr uint32_t kAll = 0xFFFFFFFFu;

std::unique_ptr<World> makeWorld() {
  WorldConfig config;
  config.frameBudgetMs = 0.0;  // no budget cuts in physics checks
  std::unique_ptr<World> world;
  EXPECT_EQ(World::create(config, &world), Status::Ok) << lastError();
  return world;
}

Collider* addGround(World& world, CollisionFilter filter = {}) {
  ColliderDesc ground;
  ground.shape.type = ShapeType::Plane;
  ground.filter = filter;
  ColliderHandle h;
  EXPECT_EQ(world.createCollider(ground, &h), Status::Ok) << lastError();
  return world.collider(h);
}

Collider* addBall(World& world, double y, CollisionFilter filter = {}) {
  ColliderDesc ball;
  ball.bodyType = BodyType::Dynamic;
  ball.shape.radius = 0.5;
  ball.pose.position = Vec3(0.0, y, 0.0);
  ball.filter = filter;
  ColliderHandle h;
  EXPECT_EQ(world.createCollider(ball, &h), Status::Ok) << lastError();
  return world.collider(h);
}

void run(World& world, int steps) {
  for (int i = 0; i < steps; ++i) ASSERT_EQ(world.step(kDt), Status::Ok);
}

TEST(CollisionFilter, MeetsWhenEachCategoryIsInTheOthersMask) {
  EXPECT_TRUE(CollisionFilter{}.meets(CollisionFilter{}));
  EXPECT_TRUE((CollisionFilter{2, 4}).meets(CollisionFilter{4, 2}));
  EXPECT_FALSE((CollisionFilter{2, 4}).meets(CollisionFilter{4, 1}));  // one way only
  EXPECT_FALSE((CollisionFilter{0, kAll}).meets(CollisionFilter{}));   // no category meets nothing
  EXPECT_TRUE((CollisionFilter{6, kAll}).meets(CollisionFilter{1, 4}));  // one shared bit is enough
}

TEST(CollisionFilter, ABallRestsOnTheGroundOnlyWhenTheyMeet) {
  struct Case {
    const char* what;
    CollisionFilter ground, ball;
    bool rests;
  } cases[] = {
      {"defaults", {}, {}, true},
      {"ball's mask leaves out the ground's category", {2, kAll}, {1, kAll & ~2u}, false},
      {"ground's mask leaves out the ball's category", {1, kAll & ~4u}, {4, kAll}, false},
      {"ball in no category", {}, {0, kAll}, false},
      {"one shared bit", {2 | 8, 4}, {4, 8}, true},
  };
  for (const Case& c : cases) {
    auto world = makeWorld();
    addGround(*world, c.ground);
    Collider* ball = addBall(*world, 2.0, c.ball);
    run(*world, 90);
    const double y = ball->pose().position.y();
    if (c.rests)
      EXPECT_NEAR(y, 0.5, 0.01) << c.what;
    else
      EXPECT_LT(y, -2.0) << c.what;  // 1.5 s of free fall from 2 m
  }
}

TEST(CollisionFilter, AChangedFilterTakesEffectAndWakesWhatRestedOnTheCollider) {
  auto world = makeWorld();
  Collider* ground = addGround(*world);
  Collider* ball = addBall(*world, 2.0);
  run(*world, 300);  // Bullet puts a body at rest for 2 s to sleep
  ASSERT_TRUE(ball->sleeping());
  ASSERT_NEAR(ball->pose().position.y(), 0.5, 0.01);
  world->setColliderFilter(*ground, CollisionFilter{2, kAll & ~1u});
  EXPECT_EQ(ground->filter().category, 2u);
  run(*world, 60);
  EXPECT_LT(ball->pose().position.y(), -2.0);

}

TEST(CollisionFilter, ABallThatMeetsTheGroundAgainLandsOnIt) {
  auto world = makeWorld();
  addGround(*world);
  Collider* ball = addBall(*world, 3.0, CollisionFilter{1, 0});
  run(*world, 10);
  world->setColliderFilter(*ball, CollisionFilter{});
  EXPECT_EQ(ball->filter().mask, kAll);
  run(*world, 120);
  EXPECT_NEAR(ball->pose().position.y(), 0.5, 0.01);
}

TEST(CollisionFilter, ADeformableContactsOnlyTheCollidersItMeets) {
  for (bool meets : {true, false}) {
    auto world = makeWorld();
    addGround(*world, CollisionFilter{2, kAll});
    DeformableDesc cube;
    cube.mesh = makeBoxTetMesh({2, 2, 2}, Vec3::Constant(0.4), Vec3::Constant(-0.2));
    cube.pose.position = Vec3(0.0, 0.5, 0.0);
    cube.material.youngsModulus = 1e5;
    cube.filter = CollisionFilter{1, meets ? kAll : kAll & ~2u};
    DeformableHandle h;
    ASSERT_EQ(world->createDeformable(std::move(cube), &h), Status::Ok) << lastError();
    run(*world, 60);
    const DeformableBody& body = *world->deformable(h);
    double minY = 1e9;
    for (int32_t i = 0; i < body.nodeCount(); ++i) minY = std::min(minY, body.positions()[3 * i + 1]);
    if (meets)
      EXPECT_GT(minY, -0.02) << "the cube rests on the ground";
    else
      EXPECT_LT(minY, -2.0) << "the cube falls through the ground";
  }
}

// A 16^3 smoke box of 1/16 m cells around a static box filling cells [6, 10) on each axis.
struct SmokeAroundABox {
  std::unique_ptr<World> world = makeWorld();
  FluidActor* fluid = nullptr;
  explicit SmokeAroundABox(CollisionFilter fluidFilter) {
    ColliderDesc box;
    box.shape.type = ShapeType::Box;
    box.shape.halfExtents = Vec3::Constant(0.125);
    box.pose.position = Vec3::Constant(0.5);
    box.filter = CollisionFilter{2, kAll};
    ColliderHandle c;
    EXPECT_EQ(world->createCollider(box, &c), Status::Ok) << lastError();
    FluidDesc smoke;
    smoke.kind = FluidKind::Smoke;
    smoke.grid.nx = smoke.grid.ny = smoke.grid.nz = 16;
    smoke.grid.h = 1.0 / 16.0;
    smoke.filter = fluidFilter;
    FluidHandle f;
    EXPECT_EQ(world->createFluid(std::move(smoke), &f), Status::Ok) << lastError();
    fluid = world->fluid(f);
  }
  // The open part of the u-face in the middle of the box.
  double openInsideTheBox() const {
    const FaceFractionField& fr = fluid->fractions();
    return fr.open[0][fr.faceIndex(0, 8, 8, 8)];
  }
};

TEST(CollisionFilter, AFluidSeesOnlyTheCollidersItMeets) {
  SmokeAroundABox seen(CollisionFilter{});
  run(*seen.world, 1);
  EXPECT_EQ(seen.openInsideTheBox(), 0.0);
  SmokeAroundABox unseen(CollisionFilter{1, kAll & ~2u});
  run(*unseen.world, 1);
  EXPECT_EQ(unseen.openInsideTheBox(), 1.0);
  // From the next step on, a changed filter adds the box to the fluid's solids.
  unseen.fluid->setCollisionFilter(CollisionFilter{});
  run(*unseen.world, 1);
  EXPECT_EQ(unseen.openInsideTheBox(), 0.0);
}

}  // namespace
}  // namespace vp

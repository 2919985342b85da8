// Every actor kind guards its step: a NaN or an absurd speed at the end of a step puts the
// actor back to its last good state (rigid bodies and deformables: the state before the step;
// fluids: the last completed step, which readers see already), flags `diverged` in the step's
// stats, and the next step goes on from there. Each case is triggered by what a careless host
// could do through the runtime (the C ABI refuses the NaN and the absurd speeds themselves).
#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "geometry/box_tet_mesh.h"
#include "world.h"
#include "world_test_util.h"

namespace vp {
namespace {

bool divergedThisStep(const World& world, ActorKind kind) {
  for (const ActorStats& a : world.lastStats().actors)
    if (a.kind == kind && a.diverged) return true;
  return false;
}

ColliderDesc dynamicBall(const Vec3& position) {
  ColliderDesc d;
  d.bodyType = BodyType::Dynamic;
  d.shape.type = ShapeType::Sphere;
  d.shape.radius = 0.25;
  d.pose.position = position;
  return d;
}

// A closed 1 m tank of 12^3 cells holding a box of liquid.
FluidDesc liquidTank(const Vec3& centre, const Vec3& halfExtents) {
  FluidDesc tank;
  tank.kind = FluidKind::Liquid;
  tank.grid.h = 1.0 / 12.0;
  tank.grid.nx = tank.grid.ny = tank.grid.nz = 12;
  FluidShape water;
  water.type = FluidShape::Type::Box;
  water.centre = centre;
  water.halfExtents = halfExtents;
  tank.initialLiquid.push_back(water);
  return tank;
}

// Two balls 3 m apart, falling for five steps; null (and a test failure) if it cannot be made.
std::unique_ptr<World> twoFallingBalls(ColliderHandle* a, ColliderHandle* b) {
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  if (!world) return nullptr;
  EXPECT_EQ(world->createCollider(dynamicBall(Vec3(0, 5, 0)), a), Status::Ok) << lastError();
  EXPECT_EQ(world->createCollider(dynamicBall(Vec3(3, 5, 0)), b), Status::Ok) << lastError();
  for (int i = 0; i < 5; ++i) EXPECT_EQ(world->step(1.0 / 60.0), Status::Ok);
  return testing::Test::HasFailure() ? nullptr : std::move(world);
}

TEST(DivergenceGuard, ARigidBodyWithANaNOrAnAbsurdSpeedGoesBackToItsStateBeforeTheStep) {
  ColliderHandle bad, good;
  std::unique_ptr<World> world = twoFallingBalls(&bad, &good);
  ASSERT_TRUE(world);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Vec3& v : {Vec3(nan, 0, 0), Vec3(0, 1e7, 0)}) {
    Collider& c = *world->collider(bad);
    const Pose pose = c.pose();
    const Vec3 angular = c.angularVelocity();
    c.setVelocity(v, angular);
    const double goodY = world->collider(good)->pose().position.y();
    ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
    EXPECT_TRUE(divergedThisStep(*world, ActorKind::Rigid));
    EXPECT_EQ(world->collider(bad)->pose().position, pose.position);
    EXPECT_TRUE(world->collider(bad)->pose().rotation.coeffs() == pose.rotation.coeffs());
    // The velocity before the step is the one the host set: the guard restores, the host's
    // value stays the host's. Put a sane one back and the body falls on.
    world->collider(bad)->setVelocity(Vec3::Zero(), angular);
    EXPECT_LT(world->collider(good)->pose().position.y(), goodY);  // the other body stepped
    ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
    EXPECT_FALSE(divergedThisStep(*world, ActorKind::Rigid));
    EXPECT_LT(world->collider(bad)->pose().position.y(), pose.position.y());
  }
}

// A small block 2 m up, in the air.
DeformableDesc blockInTheAir() {
  DeformableDesc d;
  d.mesh = makeBoxTetMesh({3, 2, 2}, Vec3(0.6, 0.4, 0.4), Vec3::Zero());
  d.pose.position = Vec3(0, 2, 0);
  return d;
}

TEST(DivergenceGuard, ADeformableDrivenToAnAbsurdSpeedGoesBackToItsStateBeforeTheStep) {
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  ASSERT_TRUE(world);
  DeformableHandle h;
  ASSERT_EQ(world->createDeformable(blockInTheAir(), &h), Status::Ok) << lastError();
  for (int i = 0; i < 3; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  DeformableBody& body = *world->deformable(h);
  const std::vector<double> x(body.positions().begin(), body.positions().end());
  const std::vector<double> v(body.velocities().begin(), body.velocities().end());
  ASSERT_EQ(body.applyForce(0, Vec3(0, 1e30, 0)), Status::Ok);  // finite, absurd
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  EXPECT_TRUE(divergedThisStep(*world, ActorKind::Deformable));
  EXPECT_TRUE(std::equal(x.begin(), x.end(), body.positions().begin()));
  EXPECT_TRUE(std::equal(v.begin(), v.end(), body.velocities().begin()));
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);  // the force was spent: it falls on
  EXPECT_FALSE(divergedThisStep(*world, ActorKind::Deformable));
  EXPECT_LT(body.positions()[1], x[1]);
}

// A step that blew up is not tried again at the same length from the same state: a body that
// a frame budget has stepping every fourth frame steps every frame once its step diverged.
TEST(DivergenceGuard, ADeformableWhoseLongStepDivergedStepsEveryFrameAgain) {
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  ASSERT_TRUE(world);
  DeformableHandle h;
  ASSERT_EQ(world->createDeformable(blockInTheAir(), &h), Status::Ok) << lastError();
  DeformableBody& body = *world->deformable(h);
  body.schedule().interval = 4;
  ASSERT_EQ(body.applyForce(0, Vec3(0, 1e30, 0)), Status::Ok);
  bool diverged = false;
  for (int i = 0; i < 4 && !diverged; ++i) {
    ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
    diverged = divergedThisStep(*world, ActorKind::Deformable);
  }
  ASSERT_TRUE(diverged);
  EXPECT_EQ(body.schedule().interval, 1);
}

// A kinematic paddle turned at an absurd rate stirs the liquid beyond any plausible speed in
// one step; the step is dropped and the fluid is its last completed step again, bit for bit.
TEST(DivergenceGuard, ADivergedFluidStepIsDroppedNotResetToRest) {
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  ASSERT_TRUE(world);
  ColliderDesc paddle;
  paddle.bodyType = BodyType::Kinematic;
  paddle.shape.type = ShapeType::Box;
  paddle.shape.halfExtents = Vec3(0.3, 0.1, 0.05);
  paddle.pose.position = Vec3(0.5, 0.2, 0.5);
  paddle.angularVelocity = Vec3(0, 2, 0);
  ColliderHandle p;
  ASSERT_EQ(world->createCollider(paddle, &p), Status::Ok) << lastError();
  FluidDesc tank = liquidTank(Vec3(0.5, 0.25, 0.5), Vec3(0.5, 0.25, 0.5));
  tank.sides[3] = DomainSide::Open;
  FluidHandle f;
  ASSERT_EQ(world->createFluid(tank, &f), Status::Ok) << lastError();
  for (int i = 0; i < 5; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  const FluidActor& fluid = *world->fluid(f);
  const MacGrid grid = fluid.grid();
  const Array<double> phi = fluid.levelSet(), pressure = fluid.pressure();
  world->collider(p)->setVelocity(Vec3::Zero(), Vec3(0, 1e7, 0));
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  EXPECT_TRUE(divergedThisStep(*world, ActorKind::Fluid));
  for (int a = 0; a < 3; ++a) EXPECT_EQ(fluid.grid().velocity[a], grid.velocity[a]) << "axis " << a;
  EXPECT_EQ(fluid.levelSet(), phi);
  EXPECT_EQ(fluid.pressure(), pressure);
  // The flow was not thrown away: it still moves as the paddle stirred it.
  double fastest = 0.0;
  for (int a = 0; a < 3; ++a)
    for (double u : fluid.grid().velocity[a]) fastest = std::max(fastest, std::abs(u));
  EXPECT_GT(fastest, 1e-3);
  world->collider(p)->setVelocity(Vec3::Zero(), Vec3(0, 2, 0));
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  EXPECT_FALSE(divergedThisStep(*world, ActorKind::Fluid));
}

// A solver that puts energy in unasked (Bullet's constraints can, with bad masses or joints):
// the ball's speed is tripled after each of Bullet's sub-steps, far below the speed bound. The
// dynamic bodies' energy is one account, so the step is undone for both balls.
void tripleTheFirstBodysSpeed(btDynamicsWorld* bullet, btScalar) {
  auto* ball = static_cast<btRigidBody*>(bullet->getWorldUserInfo());
  ball->setLinearVelocity(ball->getLinearVelocity() * btScalar(3));
}

TEST(DivergenceGuard, ARigidStepWhoseEnergyRisesBeyondItsWorkIsUndoneForEveryBody) {
  ColliderHandle a, b;
  std::unique_ptr<World> world = twoFallingBalls(&a, &b);
  ASSERT_TRUE(world);
  const Pose poseA = world->collider(a)->pose(), poseB = world->collider(b)->pose();
  const Vec3 velocityA = world->collider(a)->linearVelocity(), velocityB = world->collider(b)->linearVelocity();
  btDiscreteDynamicsWorld& bullet = world->collisionWorld().bullet();
  bullet.setInternalTickCallback(&tripleTheFirstBodysSpeed, world->collider(a)->body());
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  bullet.setInternalTickCallback(nullptr);
  EXPECT_TRUE(divergedThisStep(*world, ActorKind::Rigid));
  EXPECT_EQ(world->collider(a)->pose().position, poseA.position);
  EXPECT_EQ(world->collider(b)->pose().position, poseB.position);
  EXPECT_EQ(world->collider(a)->linearVelocity(), velocityA);
  EXPECT_EQ(world->collider(b)->linearVelocity(), velocityB);
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);  // a sound solver again: both fall on
  EXPECT_FALSE(divergedThisStep(*world, ActorKind::Rigid));
  EXPECT_LT(world->collider(a)->pose().position.y(), poseA.position.y());
  EXPECT_LT(world->collider(b)->pose().position.y(), poseB.position.y());
}

// What a moving body puts in is work, however large against the energy before: a kinematic
// bat at 10 m/s sends a resting ball off at about twice its speed, and no step is undone.
TEST(DivergenceGuard, ABatFromAKinematicBodyIsWorkNotABlowUp) {
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  ASSERT_TRUE(world);
  ASSERT_EQ(world->setGravity(Vec3::Zero()), Status::Ok);
  ColliderDesc bat;
  bat.bodyType = BodyType::Kinematic;
  bat.shape.type = ShapeType::Box;
  bat.shape.halfExtents = Vec3(0.1, 0.5, 0.5);
  bat.pose.position = Vec3(-1, 0, 0);
  bat.linearVelocity = Vec3(10, 0, 0);
  ColliderHandle batHandle, ball;
  ASSERT_EQ(world->createCollider(bat, &batHandle), Status::Ok) << lastError();
  ASSERT_EQ(world->createCollider(dynamicBall(Vec3(0, 0, 0)), &ball), Status::Ok) << lastError();
  for (int i = 0; i < 20; ++i) {
    ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
    EXPECT_FALSE(divergedThisStep(*world, ActorKind::Rigid)) << "step " << i;
  }
  EXPECT_GT(world->collider(ball)->linearVelocity().x(), 10.0);
}

// A fluid step that comes out with more kinetic energy than its sources and moving solids can
// have put in (the test hook triples its velocities before the guard, as a broken stage
// would; every speed stays far below the speed bound) is dropped like a diverged one.
TEST(DivergenceGuard, AFluidStepWhoseEnergyRisesBeyondItsSourcesIsDropped) {
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  ASSERT_TRUE(world);
  const FluidDesc tank = liquidTank(Vec3(0.2, 0.4, 0.5), Vec3(0.2, 0.4, 0.5));
  FluidHandle f;
  ASSERT_EQ(world->createFluid(tank, &f), Status::Ok) << lastError();
  for (int i = 0; i < 10; ++i) {  // a collapsing column: its energy grows fast, by gravity's work
    ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
    ASSERT_FALSE(divergedThisStep(*world, ActorKind::Fluid)) << "step " << i;
  }
  FluidActor& fluid = *world->fluid(f);
  const MacGrid grid = fluid.grid();
  const Array<double> phi = fluid.levelSet(), pressure = fluid.pressure();
  double fastest = 0.0;
  for (int a = 0; a < 3; ++a)
    for (double u : grid.velocity[a]) fastest = std::max(fastest, std::abs(u));
  ASSERT_LT(3.0 * fastest, 100.0);
  fluid.injectVelocityScaleForTesting(3.0);
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  EXPECT_TRUE(divergedThisStep(*world, ActorKind::Fluid));
  for (int a = 0; a < 3; ++a) EXPECT_EQ(fluid.grid().velocity[a], grid.velocity[a]) << "axis " << a;
  EXPECT_EQ(fluid.levelSet(), phi);
  EXPECT_EQ(fluid.pressure(), pressure);
  ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  EXPECT_FALSE(divergedThisStep(*world, ActorKind::Fluid));
}

// Smoke from rest under strong buoyancy and confinement: energy from nothing every step, all
// of it work of the body forces, which the bound explains.
TEST(DivergenceGuard, ABuoyantSmokeIsWorkNotABlowUp) {
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  ASSERT_TRUE(world);
  FluidDesc smoke;
  smoke.grid.h = 1.0 / 16.0;
  smoke.grid.nx = smoke.grid.ny = smoke.grid.nz = 16;
  smoke.smoke.thermalBuoyancy = 20.0;
  smoke.smoke.vorticityConfinement = 2.0;
  FluidEmitter source;
  source.shape.type = FluidShape::Type::Sphere;
  source.shape.centre = Vec3(0.5, 0.15, 0.5);
  source.shape.radius = 0.12;
  source.temperature = 5.0;
  smoke.emitters.push_back(source);
  FluidHandle f;
  ASSERT_EQ(world->createFluid(smoke, &f), Status::Ok) << lastError();
  for (int i = 0; i < 60; ++i) {
    ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
    ASSERT_FALSE(divergedThisStep(*world, ActorKind::Fluid)) << "step " << i;
  }
}

}  // namespace
}  // namespace vp

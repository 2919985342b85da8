// Host control of rigid bodies: loads, impulses, run-time properties, sleeping. Expected
// velocities come from Newton's laws for a solid sphere (I = 2/5 m r^2) in zero gravity; Bullet
// integrates a constant load exactly over its sub-steps (symplectic Euler on the velocity), so
// the tolerances are float round-off.
#include <cmath>

#include "capi_test_support.h"

namespace {

constexpr float kMass = 2.0f, kRadius = 0.5f;
constexpr float kInertia = 0.4f * kMass * kRadius * kRadius;
constexpr float kDt = 1.0f / 60.0f;
constexpr float kTol = 1e-5f;

vpWorldDef weightless() {
  vpWorldDef def = unbudgetedWorldDef();
  def.gravity = vpVec3{0, 0, 0};
  return def;
}

// A free sphere at (0, 2, 0) without damping, so velocities change by the loads alone.
vpColliderId freeSphere(vpWorldId world, float mass = kMass) {
  vpColliderDef def = dynamicBall(2.0f, kRadius);
  def.mass = mass;
  def.linearDamping = 0.0f;
  def.angularDamping = 0.0f;
  vpColliderId id{};
  EXPECT_VP_OK(vpColliderCreate(world, &def, &id));
  return id;
}

struct Velocity {
  vpVec3 linear{}, angular{};
};
Velocity velocityOf(vpColliderId id) {
  Velocity v;
  EXPECT_VP_OK(vpColliderGetVelocity(id, &v.linear, &v.angular));
  return v;
}

void expectVec(const vpVec3& v, float x, float y, float z, float tol = kTol) {
  EXPECT_NEAR(v.x, x, tol);
  EXPECT_NEAR(v.y, y, tol);
  EXPECT_NEAR(v.z, z, tol);
}

vpBodyProperties propertiesOf(vpColliderId id) {
  vpBodyProperties p{};
  p.structSize = sizeof p;
  EXPECT_VP_OK(vpColliderGetProperties(id, &p));
  return p;
}

TEST(CApiRigidBody, ImpulseChangesTheVelocityAtOnceByImpulseOverMass) {
  ScopedWorld w(weightless());
  const vpColliderId ball = freeSphere(w.id);
  ASSERT_VP_OK(vpColliderApplyImpulse(ball, vpVec3{4, 0, -1}, nullptr));
  const Velocity v = velocityOf(ball);
  expectVec(v.linear, 4 / kMass, 0, -1 / kMass);
  expectVec(v.angular, 0, 0, 0);
  // Then it coasts: no load is left over for the step.
  ASSERT_VP_OK(vpWorldStep(w.id, kDt));
  expectVec(velocityOf(ball).linear, 4 / kMass, 0, -1 / kMass);
}

TEST(CApiRigidBody, ImpulseAtAPointAlsoSpinsByInverseInertiaTimesMoment) {
  ScopedWorld w(weightless());
  const vpColliderId ball = freeSphere(w.id);
  // J = (0, 0, 1) at r = (0.5, 0, 0) from the centre: r x J = (0, -0.5, 0).
  const vpVec3 point{kRadius, 2.0f, 0.0f};
  ASSERT_VP_OK(vpColliderApplyImpulse(ball, vpVec3{0, 0, 1}, &point));
  const Velocity v = velocityOf(ball);
  expectVec(v.linear, 0, 0, 1 / kMass);
  expectVec(v.angular, 0, -kRadius / kInertia, 0);
}

TEST(CApiRigidBody, AngularImpulseSpinsByInverseInertia) {
  ScopedWorld w(weightless());
  const vpColliderId ball = freeSphere(w.id);
  ASSERT_VP_OK(vpColliderApplyAngularImpulse(ball, vpVec3{0.3f, 0, 0}));
  const Velocity v = velocityOf(ball);
  expectVec(v.linear, 0, 0, 0);
  expectVec(v.angular, 0.3f / kInertia, 0, 0);
}

TEST(CApiRigidBody, ForceActsForOneWholeStepThenIsCleared) {
  ScopedWorld w(weightless());
  const vpColliderId ball = freeSphere(w.id);
  // Two forces before one step add up; neither changes the velocity before the step.
  ASSERT_VP_OK(vpColliderApplyForce(ball, vpVec3{4, 0, 0}, nullptr));
  ASSERT_VP_OK(vpColliderApplyForce(ball, vpVec3{2, -3, 0}, nullptr));
  expectVec(velocityOf(ball).linear, 0, 0, 0);
  ASSERT_VP_OK(vpWorldStep(w.id, kDt));  // two rigid sub-steps at the default 1/120 s
  expectVec(velocityOf(ball).linear, 6 * kDt / kMass, -3 * kDt / kMass, 0);
  ASSERT_VP_OK(vpWorldStep(w.id, kDt));
  expectVec(velocityOf(ball).linear, 6 * kDt / kMass, -3 * kDt / kMass, 0);
  expectVec(velocityOf(ball).angular, 0, 0, 0);
}

TEST(CApiRigidBody, ForceAtAPointAndTorqueTurnTheBody) {
  ScopedWorld w(weightless());
  const vpColliderId ball = freeSphere(w.id);
  const vpVec3 point{0.0f, 2.0f + kRadius, 0.0f};  // r = (0, 0.5, 0); r x (1, 0, 0) = (0, 0, -0.5)
  ASSERT_VP_OK(vpColliderApplyForce(ball, vpVec3{1, 0, 0}, &point));
  ASSERT_VP_OK(vpColliderApplyTorque(ball, vpVec3{0.2f, 0, 0}));
  ASSERT_VP_OK(vpWorldStep(w.id, kDt));
  const Velocity v = velocityOf(ball);
  expectVec(v.linear, kDt / kMass, 0, 0);
  expectVec(v.angular, 0.2f * kDt / kInertia, 0, -kRadius * kDt / kInertia);
}

TEST(CApiRigidBody, DoublingTheMassHalvesWhatAnImpulseDoesAndRescalesTheInertia) {
  ScopedWorld w(weightless());
  const vpColliderId ball = freeSphere(w.id);
  vpBodyProperties p = propertiesOf(ball);
  EXPECT_FLOAT_EQ(p.mass, kMass);
  p.mass = 2 * kMass;
  p.friction = 0.9f;
  p.restitution = 0.25f;
  p.linearDamping = 0.1f;
  p.angularDamping = 0.2f;
  ASSERT_VP_OK(vpColliderSetProperties(ball, &p));
  const vpBodyProperties read = propertiesOf(ball);
  EXPECT_FLOAT_EQ(read.mass, 2 * kMass);
  EXPECT_FLOAT_EQ(read.friction, 0.9f);
  EXPECT_FLOAT_EQ(read.restitution, 0.25f);
  EXPECT_FLOAT_EQ(read.linearDamping, 0.1f);
  EXPECT_FLOAT_EQ(read.angularDamping, 0.2f);
  const vpVec3 point{kRadius, 2.0f, 0.0f};
  ASSERT_VP_OK(vpColliderApplyImpulse(ball, vpVec3{0, 0, 1}, &point));
  const Velocity v = velocityOf(ball);
  expectVec(v.linear, 0, 0, 1 / (2 * kMass));
  expectVec(v.angular, 0, -kRadius / (2 * kInertia), 0);
}

TEST(CApiRigidBody, RestitutionSetAtRunTimeMakesADroppedBallBounce) {
  // A ball dropped on a static floor: with restitution 0 on both it stays down; after raising
  // the ball's and the floor's to 1 (Bullet multiplies them) it comes back up.
  ScopedWorld w;
  vpColliderDef floor = vpDefaultColliderDef();
  floor.shape.type = vpShapeType_Plane;
  floor.shape.normal = vpVec3{0, 1, 0};
  vpColliderId ground{};
  ASSERT_VP_OK(vpColliderCreate(w.id, &floor, &ground));
  const vpColliderId ball = freeSphere(w.id);
  for (vpColliderId id : {ground, ball}) {
    vpBodyProperties p = propertiesOf(id);
    p.restitution = 1.0f;
    ASSERT_VP_OK(vpColliderSetProperties(id, &p));
  }
  float lowest = 10.0f, highestAfterLowest = -1.0f;
  for (int i = 0; i < 120; ++i) {
    ASSERT_VP_OK(vpWorldStep(w.id, kDt));
    vpTransform pose{};
    ASSERT_VP_OK(vpColliderGetPose(ball, &pose));
    if (pose.position.y < lowest) {
      lowest = pose.position.y;
      highestAfterLowest = -1.0f;
    }
    highestAfterLowest = std::fmax(highestAfterLowest, pose.position.y);
  }
  EXPECT_LT(lowest, kRadius + 0.05f);
  EXPECT_GT(highestAfterLowest, 1.0f);  // dropped from 2 m, most of the height comes back
}

TEST(CApiRigidBody, BadLoadsAndPropertiesAreNamedAndChangeNothing) {
  ScopedWorld w(weightless());
  const vpColliderId ball = freeSphere(w.id);
  const vpVec3 farPoint{1e30f, 0, 0}, nanPoint{NAN, 0, 0};
  const vpVec3 edge{0.0f, 9e5f, 0.0f};  // a legal point and impulse whose moment is out of range
  EXPECT_EQ(vpColliderApplyForce(ball, vpVec3{NAN, 0, 0}, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("force = (nan")) << vpGetLastError();
  EXPECT_EQ(vpColliderApplyForce(ball, vpVec3{0, 1e20f, 0}, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("force = (0, 1e+20, 0)")) << vpGetLastError();
  EXPECT_EQ(vpColliderApplyForce(ball, vpVec3{1, 0, 0}, &farPoint), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("point = (1e+30")) << vpGetLastError();
  EXPECT_EQ(vpColliderApplyImpulse(ball, vpVec3{1, 0, 0}, &nanPoint), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("point = (nan")) << vpGetLastError();
  EXPECT_EQ(vpColliderApplyImpulse(ball, vpVec3{5e13f, 0, 0}, &edge), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("moment")) << vpGetLastError();
  EXPECT_EQ(vpColliderApplyTorque(ball, vpVec3{0, 0, INFINITY}), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("torque = (0, 0, inf")) << vpGetLastError();
  EXPECT_EQ(vpColliderApplyAngularImpulse(ball, vpVec3{0, -1e15f, 0}), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("angularImpulse = (0, -1e+15")) << vpGetLastError();

  const vpBodyProperties good = propertiesOf(ball);
  struct PropertyCase {
    const char* message;
    vpStatus status;
    void (*mutate)(vpBodyProperties&);
  } cases[] = {
      {"vpBodyProperties.structSize = 6", vpStatus_VersionMismatch, [](vpBodyProperties& p) { p.structSize = 6; }},
      {"mass = 0", vpStatus_InvalidArgument, [](vpBodyProperties& p) { p.mass = 0; }},
      {"mass = nan", vpStatus_InvalidArgument, [](vpBodyProperties& p) { p.mass = NAN; }},
      {"mass = 1e+12", vpStatus_InvalidArgument, [](vpBodyProperties& p) { p.mass = 1e12f; }},
      {"friction = -1", vpStatus_InvalidArgument, [](vpBodyProperties& p) { p.friction = -1; }},
      {"restitution = 1.5", vpStatus_InvalidArgument, [](vpBodyProperties& p) { p.restitution = 1.5f; }},
      {"linearDamping = inf", vpStatus_InvalidArgument, [](vpBodyProperties& p) { p.linearDamping = INFINITY; }},
      {"angularDamping = -0.5", vpStatus_InvalidArgument, [](vpBodyProperties& p) { p.angularDamping = -0.5f; }},
  };
  for (const PropertyCase& c : cases) {
    vpBodyProperties p = good;
    p.mass = 7;  // a valid change that must not survive the failed call
    c.mutate(p);
    EXPECT_EQ(vpColliderSetProperties(ball, &p), c.status) << c.message;
    EXPECT_TRUE(lastErrorContains(c.message)) << c.message << " / " << vpGetLastError();
    const vpBodyProperties now = propertiesOf(ball);
    EXPECT_EQ(now.mass, good.mass) << c.message;
    EXPECT_EQ(now.friction, good.friction) << c.message;
  }
  EXPECT_EQ(vpColliderSetProperties(ball, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("properties")) << vpGetLastError();
  EXPECT_EQ(vpColliderGetProperties(ball, nullptr), vpStatus_InvalidArgument);
  EXPECT_EQ(vpColliderIsSleeping(ball, nullptr), vpStatus_InvalidArgument);
  EXPECT_TRUE(lastErrorContains("outSleeping")) << vpGetLastError();

  // None of the failed calls left a load or a velocity behind.
  ASSERT_VP_OK(vpWorldStep(w.id, kDt));
  const Velocity v = velocityOf(ball);
  expectVec(v.linear, 0, 0, 0);
  expectVec(v.angular, 0, 0, 0);
}

TEST(CApiRigidBody, StaticAndKinematicBodiesCannotBePushedOrPutToSleep) {
  ScopedWorld w(weightless());
  for (vpBodyType type : {vpBodyType_Static, vpBodyType_Kinematic}) {
    vpColliderDef def = vpDefaultColliderDef();
    def.bodyType = type;
    vpColliderId id{};
    ASSERT_VP_OK(vpColliderCreate(w.id, &def, &id));
    const char* name = type == vpBodyType_Static ? "is static" : "is kinematic";
    EXPECT_EQ(vpColliderApplyForce(id, vpVec3{1, 0, 0}, nullptr), vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains(name)) << vpGetLastError();
    EXPECT_EQ(vpColliderApplyImpulse(id, vpVec3{1, 0, 0}, nullptr), vpStatus_InvalidArgument);
    EXPECT_EQ(vpColliderApplyTorque(id, vpVec3{1, 0, 0}), vpStatus_InvalidArgument);
    EXPECT_EQ(vpColliderApplyAngularImpulse(id, vpVec3{1, 0, 0}), vpStatus_InvalidArgument);
    EXPECT_EQ(vpColliderSetSleeping(id, 1), vpStatus_InvalidArgument);
    EXPECT_TRUE(lastErrorContains(name)) << vpGetLastError();
    int32_t sleeping = -1;
    ASSERT_VP_OK(vpColliderIsSleeping(id, &sleeping));
    EXPECT_EQ(sleeping, 0);
    // Their material can change; they have no mass (0 is returned, and what is set is ignored).
    vpBodyProperties p = propertiesOf(id);
    EXPECT_EQ(p.mass, 0.0f);
    p.friction = 0.1f;
    p.mass = 0.0f;
    ASSERT_VP_OK(vpColliderSetProperties(id, &p));
    EXPECT_FLOAT_EQ(propertiesOf(id).friction, 0.1f);
  }
}

TEST(CApiRigidBody, ASleepingBodyStaysPutUnderGravityUntilWokenOrPushed) {
  ScopedWorld w;  // default gravity
  const vpColliderId ball = freeSphere(w.id);
  ASSERT_VP_OK(vpColliderApplyImpulse(ball, vpVec3{1, 0, 0}, nullptr));
  int32_t sleeping = -1;
  ASSERT_VP_OK(vpColliderIsSleeping(ball, &sleeping));
  EXPECT_EQ(sleeping, 0);
  ASSERT_VP_OK(vpColliderSetSleeping(ball, 1));
  ASSERT_VP_OK(vpColliderIsSleeping(ball, &sleeping));
  EXPECT_EQ(sleeping, 1);
  expectVec(velocityOf(ball).linear, 0, 0, 0);
  for (int i = 0; i < 30; ++i) ASSERT_VP_OK(vpWorldStep(w.id, kDt));
  vpTransform pose{};
  ASSERT_VP_OK(vpColliderGetPose(ball, &pose));
  EXPECT_EQ(pose.position.y, 2.0f);

  ASSERT_VP_OK(vpColliderSetSleeping(ball, 0));
  ASSERT_VP_OK(vpColliderIsSleeping(ball, &sleeping));
  EXPECT_EQ(sleeping, 0);
  ASSERT_VP_OK(vpWorldStep(w.id, kDt));
  ASSERT_VP_OK(vpColliderGetPose(ball, &pose));
  EXPECT_LT(pose.position.y, 2.0f);  // falling again

  // A push wakes a sleeping body too.
  ASSERT_VP_OK(vpColliderSetSleeping(ball, 1));
  ASSERT_VP_OK(vpColliderApplyForce(ball, vpVec3{0, 0, 1}, nullptr));
  ASSERT_VP_OK(vpColliderIsSleeping(ball, &sleeping));
  EXPECT_EQ(sleeping, 0);
}

TEST(CApiRigidBody, AStaleOrWrongKindIdIsRefused) {
  ScopedWorld w(weightless());
  const vpColliderId ball = freeSphere(w.id);
  ASSERT_VP_OK(vpColliderDestroy(ball));
  EXPECT_EQ(vpColliderApplyImpulse(ball, vpVec3{1, 0, 0}, nullptr), vpStatus_InvalidId);
  vpBodyProperties p{};
  p.structSize = sizeof p;
  EXPECT_EQ(vpColliderGetProperties(ball, &p), vpStatus_InvalidId);
  EXPECT_EQ(vpColliderSetSleeping(ball, 1), vpStatus_InvalidId);
}

}  // namespace

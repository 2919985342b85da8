// Deformables push dynamic rigid bodies: the impulses a deformable's contacts apply to its
// nodes act, equal and opposite, on the Bullet body they touch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "geometry/box_tet_mesh.h"
#include "world.h"
#include "world_test_util.h"

namespace vp {
namespace {

struct ZeroGravityScene {
  std::unique_ptr<World> world;
  DeformableHandle jelly{};
  ColliderHandle ball{};
  double ballMass = 1.0;

  ZeroGravityScene() {
    WorldConfig config;
    config.workerCount = 2;
    config.frameBudgetMs = 0.0;  // no budget cuts
    config.gravity = Vec3::Zero();
    EXPECT_EQ(World::create(config, &world), Status::Ok) << lastError();
    // A 0.4 m jelly of density 100 (6.4 kg) at 3 m/s towards a 1 kg ball at rest.
    DeformableDesc d;
    d.mesh = makeBoxTetMesh({4, 4, 4}, Vec3::Constant(0.4), Vec3::Constant(-0.2));
    d.material.youngsModulus = 2e4;
    d.material.density = 100.0;
    d.material.friction = 0.0;
    d.solver.tolerance = 1e-6;
    d.solver.maxIterations = 500;
    d.linearVelocity = Vec3(3.0, 0.0, 0.0);
    EXPECT_EQ(world->createDeformable(std::move(d), &jelly), Status::Ok) << lastError();
    ColliderDesc b;
    b.bodyType = BodyType::Dynamic;
    b.shape.radius = 0.2;
    b.mass = ballMass;
    b.friction = 0.0;
    b.linearDamping = 0.0;
    b.angularDamping = 0.0;
    b.pose.position = Vec3(0.6, 0.0, 0.0);
    EXPECT_EQ(world->createCollider(b, &ball), Status::Ok) << lastError();
  }
  Vec3 jellyMomentum() {
    const DeformableBody& body = *world->deformable(jelly);
    Vec3 p = Vec3::Zero();
    for (int32_t i = 0; i < body.nodeCount(); ++i)
      p += body.nodeMasses()[i] * Vec3(body.velocities()[3 * i], body.velocities()[3 * i + 1], body.velocities()[3 * i + 2]);
    return p;
  }
  double jellyMass() {
    double m = 0.0;
    for (double mi : world->deformable(jelly)->nodeMasses()) m += mi;
    return m;
  }
};

TEST(DeformablePushesRigid, AJellyHittingABallConservesMomentumAndSendsItOff) {
  ZeroGravityScene s;
  const Vec3 before = s.jellyMomentum();
  ASSERT_NEAR(before.x(), 3.0 * s.jellyMass(), 1e-9 * before.norm());
  for (int i = 0; i < 90; ++i) ASSERT_EQ(s.world->step(1.0 / 60.0), Status::Ok);
  const Vec3 ballVelocity = s.world->collider(s.ball)->linearVelocity();
  const Vec3 after = s.jellyMomentum() + s.ballMass * ballVelocity;
  EXPECT_LT((after - before).norm(), 0.02 * before.norm()) << "after " << after.transpose();
  // Between a perfectly inelastic collision (both at the common speed) and an elastic one.
  const double mj = s.jellyMass(), mb = s.ballMass, v = 3.0;
  EXPECT_GE(ballVelocity.x(), mj * v / (mj + mb) * 0.98);
  EXPECT_LE(ballVelocity.x(), 2.0 * mj * v / (mj + mb) * 1.02);
  // The ball went off ahead of the jelly, which slowed down.
  EXPECT_LT(s.jellyMomentum().x() / mj, v);
}


// A world under gravity with a static ground plane at y = 0.
std::unique_ptr<World> groundWorld() {
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  if (!world) return world;
  ColliderDesc ground;
  ground.bodyType = BodyType::Static;
  ground.shape.type = ShapeType::Plane;
  ColliderHandle handle;
  EXPECT_EQ(world->createCollider(ground, &handle), Status::Ok) << lastError();
  return world;
}

ColliderDesc dynamicBox(const Vec3& halfExtents, double mass, const Vec3& centre) {
  ColliderDesc b;
  b.bodyType = BodyType::Dynamic;
  b.shape.type = ShapeType::Box;
  b.shape.halfExtents = halfExtents;
  b.mass = mass;
  b.pose.position = centre;
  return b;
}

// A 0.4 m jelly cube (4 x 4 x 4 cells) whose lowest corner is at `lowCorner`.
DeformableDesc jellyCube(const Vec3& lowCorner, double density) {
  DeformableDesc d;
  d.mesh = makeBoxTetMesh({4, 4, 4}, Vec3::Constant(0.4), lowCorner);
  d.material.youngsModulus = 2e4;
  d.material.density = density;
  d.solver.tolerance = 1e-5;
  d.solver.maxIterations = 500;
  return d;
}

double lowestY(const DeformableBody& body) {
  double y = 1e30;
  for (int32_t i = 0; i < body.nodeCount(); ++i) y = std::min(y, body.positions()[3 * i + 1]);
  return y;
}

double highestY(const DeformableBody& body) {
  double y = -1e30;
  for (int32_t i = 0; i < body.nodeCount(); ++i) y = std::max(y, body.positions()[3 * i + 1]);
  return y;
}

// A jelly (19 kg) resting on a 20 kg box resting on the ground: the jelly's weight reaches the
// box (its contacts' reactions), and the box, pressed onto the ground, neither sinks nor drifts.
TEST(DeformablePushesRigid, AJellyOnADynamicBoxOnTheGroundStaysPut) {
  std::unique_ptr<World> world = groundWorld();
  const Vec3 half(0.3, 0.1, 0.3);
  ColliderHandle box;
  ASSERT_EQ(world->createCollider(dynamicBox(half, 20.0, Vec3(0, half.y(), 0)), &box), Status::Ok) << lastError();
  // Let the box settle on the ground first: its resting height is Bullet's, not ours.
  for (int i = 0; i < 30; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  const Vec3 settled = world->collider(box)->pose().position;
  DeformableHandle jelly;
  ASSERT_EQ(world->createDeformable(jellyCube(Vec3(-0.2, settled.y() + half.y() + 0.005, -0.2), 300.0), &jelly),
            Status::Ok)
      << lastError();
  const DeformableBody& body = *world->deformable(jelly);
  const int frames = 120, lastSecond = 60;
  double pushSum = 0.0;  // the reactions' vertical impulses on the box over the last second
  for (int i = 0; i < frames; ++i) {
    ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
    if (i >= frames - lastSecond)
      for (const ContactReaction& r : body.contactReactions()) pushSum += r.impulse.y();
  }
  double jellyMass = 0.0;
  for (double m : body.nodeMasses()) jellyMass += m;
  // Over a second at rest, the impulses on the box add up to the jelly's weight times 1 s.
  const double meanPush = pushSum / (lastSecond / 60.0);
  std::printf("jelly on a box: mean push on the box %.2f N, the jelly's weight %.2f N\n", meanPush, jellyMass * 9.81);
  EXPECT_NEAR(meanPush, -jellyMass * 9.81, 0.02 * jellyMass * 9.81);
  const Vec3 moved = world->collider(box)->pose().position - settled;
  std::printf("jelly on a box: the box moved (%.2e, %.2e, %.2e) m in 2 s; the jelly's bottom is %.4f m above the "
              "box's top\n",
              moved.x(), moved.y(), moved.z(), lowestY(body) - (world->collider(box)->pose().position.y() + half.y()));
  EXPECT_LT(moved.norm(), 1e-3);
  // The jelly rests on the box (within its contact margin), not in it or fallen off.
  EXPECT_NEAR(lowestY(body), world->collider(box)->pose().position.y() + half.y(), 0.01);
}

// A 2 kg box dropped from 0.3 m onto a jelly pinned at its base: the jelly stops it and
// carries it, the box at rest on its top.
// Disabled: fails. The box bounces on the jelly without losing height (up to 1 m/s rebounds
// after 40 frames), drifts to a corner and passes between the top nodes to the ground within
// 1.5 s. A box covering the whole top face is not thrown off but never rests either (2 kg:
// thrown off the side; 10 kg and 40 kg: 0.1-0.3 m/s of vertical jitter after 3 s, drifting).
// The contact holds the node to the body's frame-start velocity and sends the reaction a frame
// late (docs/choices.md, "Contacts"): against a light or resting body that loop gains energy.
// Node-against-collider contact also lets a box's edge pass between surface nodes.
TEST(DeformablePushesRigid, DISABLED_ABoxDroppedOnAPinnedJellyIsStopped) {
  std::unique_ptr<World> world = groundWorld();
  DeformableDesc d = jellyCube(Vec3(-0.2, 0.0, -0.2), 300.0);
  DeformableHandle jelly;
  ASSERT_EQ(world->createDeformable(std::move(d), &jelly), Status::Ok) << lastError();
  DeformableBody& body = *world->deformable(jelly);
  std::vector<int32_t> base;
  for (int32_t i = 0; i < body.nodeCount(); ++i)
    if (body.positions()[3 * i + 1] < 1e-9) base.push_back(i);
  ASSERT_EQ(body.setPinned(base.data(), static_cast<int64_t>(base.size()), true), Status::Ok);
  const Vec3 half(0.1, 0.05, 0.1);
  ColliderHandle box;
  ASSERT_EQ(world->createCollider(dynamicBox(half, 2.0, Vec3(0, 0.4 + 0.3 + half.y(), 0)), &box), Status::Ok)
      << lastError();
  for (int i = 0; i < 180; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  const Collider& c = *world->collider(box);
  const double gap = c.pose().position.y() - half.y() - highestY(body);
  std::printf("box on a pinned jelly after 3 s: speed %.4f m/s, its bottom %.4f m from the jelly's top\n",
              c.linearVelocity().norm(), gap);
  EXPECT_LT(c.linearVelocity().norm(), 0.05);
  EXPECT_NEAR(gap, 0.0, 0.01);
}

}  // namespace
}  // namespace vp

// Deformables push dynamic rigid bodies: the impulses a deformable's contacts apply to its
// nodes act, equal and opposite, on the Bullet body they touch.
#include <gtest/gtest.h>

#include "geometry/box_tet_mesh.h"
#include "world.h"

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

}  // namespace
}  // namespace vp

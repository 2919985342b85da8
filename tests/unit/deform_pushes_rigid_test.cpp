// Deformables push dynamic rigid bodies: the impulses a deformable's contacts apply to its
// nodes act, equal and opposite, on the Bullet body they touch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
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
  // The ball's momentum with the impulses the last step left for the next rigid step.
  Vec3 ballMomentum() {
    const Collider& c = *world->collider(ball);
    return ballMass * c.linearVelocity() + c.pendingContactImpulse();
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
  const Vec3 ballVelocity = s.ballMomentum() / s.ballMass;
  const Vec3 after = s.jellyMomentum() + s.ballMomentum();
  std::printf("jelly hits a ball: the ball at %.3f m/s, momentum %.4f -> %.4f (relative change %.1e)\n",
              ballVelocity.x(), before.x(), after.x(), (after - before).norm() / before.norm());
  EXPECT_LT((after - before).norm(), 0.02 * before.norm()) << "after " << after.transpose();
  // Between a perfectly inelastic collision (both at the common speed) and an elastic one.
  const double mj = s.jellyMass(), mb = s.ballMass, v = 3.0;
  EXPECT_GE(ballVelocity.x(), mj * v / (mj + mb) * 0.98);
  EXPECT_LE(ballVelocity.x(), 2.0 * mj * v / (mj + mb) * 1.02);
  // The ball went off ahead of the jelly, which slowed down.
  EXPECT_LT(s.jellyMomentum().x() / mj, v);
}


// The same jelly hits a 1 kg cube off its centre: the cube spins off, and the angular momentum
// about the origin is conserved with the linear one (the contacts' impulses act at the arms the
// solve used). A cube's inertia is isotropic, so Bullet's free flight keeps its spin's momentum.
TEST(DeformablePushesRigid, AnOffCentreHitConservesAngularMomentumAndSpinsTheBody) {
  ZeroGravityScene s;
  ASSERT_EQ(s.world->destroyCollider(s.ball), Status::Ok);
  ColliderDesc b;
  b.bodyType = BodyType::Dynamic;
  b.shape.type = ShapeType::Box;
  b.shape.halfExtents = Vec3::Constant(0.15);
  b.mass = s.ballMass;
  b.friction = 0.0;
  b.linearDamping = 0.0;
  b.angularDamping = 0.0;
  b.pose.position = Vec3(0.6, 0.25, 0.0);  // its lower part meets the jelly's upper part
  ASSERT_EQ(s.world->createCollider(b, &s.ball), Status::Ok) << lastError();
  // Angular momenta about the origin, where the jelly's is zero to begin with.
  auto jellyAngularMomentum = [&] {
    const DeformableBody& body = *s.world->deformable(s.jelly);
    Vec3 L = Vec3::Zero();
    for (int32_t i = 0; i < body.nodeCount(); ++i) {
      const Vec3 x(body.positions()[3 * i], body.positions()[3 * i + 1], body.positions()[3 * i + 2]);
      const Vec3 v(body.velocities()[3 * i], body.velocities()[3 * i + 1], body.velocities()[3 * i + 2]);
      L += body.nodeMasses()[i] * x.cross(v);
    }
    return L;
  };
  // The cube's, without and with the moment of the impulses the jelly's last step left for it.
  auto cubeOwnAngularMomentum = [&] {
    const Collider& c = *s.world->collider(s.ball);
    const double I = s.ballMass * 2.0 * 0.15 * 0.15 / 3.0;  // a cube's, about any axis through its centre
    return Vec3(s.ballMass * c.pose().position.cross(c.linearVelocity()) + I * c.angularVelocity());
  };
  auto cubeAngularMomentum = [&] { return Vec3(cubeOwnAngularMomentum() + s.world->collider(s.ball)->pendingContactMoment()); };
  const Vec3 linearBefore = s.jellyMomentum(), angularBefore = jellyAngularMomentum() + cubeAngularMomentum();
  // Frame by frame, the cube's rigid step changes its angular momentum by the moment of the
  // reactions the jelly's contacts recorded in the frame before (Bullet in single precision).
  Vec3 reactionMoment = Vec3::Zero();
  double largestMiss = 0.0, largestChange = 0.0, exchanged = 0.0;
  for (int i = 0; i < 60; ++i) {
    const Vec3 own = cubeOwnAngularMomentum();
    ASSERT_EQ(s.world->step(1.0 / 60.0), Status::Ok);
    const Vec3 change = cubeOwnAngularMomentum() - own;
    largestMiss = std::max(largestMiss, (change - reactionMoment).norm());
    largestChange = std::max(largestChange, change.norm());
    exchanged += change.norm();
    reactionMoment = Vec3::Zero();
    for (const ContactReaction& r : s.world->deformable(s.jelly)->contactReactions())
      reactionMoment += r.point.cross(r.impulse);
  }
  EXPECT_LT(largestMiss, 1e-4 * largestChange);
  const Collider& cube = *s.world->collider(s.ball);
  const Vec3 linearAfter = s.jellyMomentum() + s.ballMomentum();
  const Vec3 cubeL = cubeAngularMomentum();
  const Vec3 angularAfter = jellyAngularMomentum() + cubeL;
  std::printf("off-centre hit: cube at %.3f m/s, spin %.3f rad/s; angular momentum about the origin %.5f -> %.5f "
              "(z), the cube's %.5f, %.5f exchanged in all; a frame's exchange missed by at most %.1e of %.3f\n",
              cube.linearVelocity().norm(), cube.angularVelocity().norm(), angularBefore.z(), angularAfter.z(),
              cubeL.z(), exchanged, largestMiss, largestChange);
  EXPECT_GT(cube.linearVelocity().x(), 1.0);
  // The push below its centre turns it: positive z spin for a push along +x under the centre.
  EXPECT_GT(cube.angularVelocity().z(), 0.1);
  EXPECT_LT((linearAfter - linearBefore).norm(), 0.02 * linearBefore.norm());
  // The cube takes the moment of the contacts' reactions exactly (above), and they act at the
  // nodes. The jelly's own steps keep it less well: their linearized corotated stiffness exerts
  // a small net moment while it is squashed. Within 3% of the angular momentum the contacts
  // passed to the cube, frame by frame (not of the cube's final one about the origin, a sum of
  // its orbital and spin parts that nearly cancel when its corners catch on the jelly).
  EXPECT_LT((angularAfter - angularBefore).norm(), 0.03 * exchanged);
}

// A world under gravity with a static ground plane at y = 0.
std::unique_ptr<World> groundWorld(int workers = 2) {
  std::unique_ptr<World> world = testutil::unbudgetedWorld(workers);
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

// A 0.4 m jelly pinned at its base (top nodes 0.1 m apart) with a box of `mass` and half
// width `halfWidth` dropped on it from `height`.
struct BoxOnPinnedJelly {
  std::unique_ptr<World> world;
  DeformableHandle jelly{};
  ColliderHandle box{};
  Vec3 half;

  // The box's centre over (offset, offset) in x and z, its bottom `height` above the jelly's top.
  BoxOnPinnedJelly(double mass, double halfWidth, double height, double offset = 0.0, int workers = 2)
      : world(groundWorld(workers)), half(halfWidth, 0.05, halfWidth) {
    EXPECT_EQ(world->createDeformable(jellyCube(Vec3(-0.2, 0.0, -0.2), 300.0), &jelly), Status::Ok) << lastError();
    DeformableBody& body = *world->deformable(jelly);
    std::vector<int32_t> base;
    for (int32_t i = 0; i < body.nodeCount(); ++i)
      if (body.positions()[3 * i + 1] < 1e-9) base.push_back(i);
    EXPECT_EQ(body.setPinned(base.data(), static_cast<int64_t>(base.size()), true), Status::Ok);
    EXPECT_EQ(world->createCollider(dynamicBox(half, mass, Vec3(offset, 0.4 + height + half.y(), offset)), &box),
              Status::Ok)
        << lastError();
  }

  struct Rest {
    double fastest = 0.0;  // the box's largest speed over a frame in the last half second (m/s)
    double drift = 0.0;    // how far it moved in the last half second (m)
    double gap = 0.0;      // its bottom less the jelly's highest node at the end (m)
    double readSpeed = 0.0;    // the speed a host reads after the last step (m/s)
    int begins = 0, ends = 0;  // contact events between the jelly and the box
    int frames = 0;
    // At rest on the jelly's top: no frame faster than 5 cm/s and under a millimetre moved over
    // the last half second, its bottom within a centimetre of the top.
    void expectAtRest() const {
      EXPECT_LT(fastest, 0.05);
      EXPECT_LT(drift, 1e-3);
      EXPECT_NEAR(gap, 0.0, 0.01);
    }
    void print(const char* label) const {
      std::printf("%s on a pinned jelly after %.0f s: over the last 0.5 s at most %.4f m/s, moved %.2e m; its bottom "
                  "%.4f m from the jelly's top; read speed %.4f m/s; %d contact begin(s), %d end(s)\n",
                  label, frames / 60.0, fastest, drift, gap, readSpeed, begins, ends);
    }
  };
  // Its speed is read from its motion over each frame: the velocity a host reads after a step
  // holds the jelly's last push, which the next frame's gravity takes back.
  Rest run(int frames) {
    const double dt = 1.0 / 60.0;
    const int lastHalfSecond = 30;
    Rest rest;
    Vec3 before = world->collider(box)->pose().position, halfSecondAgo = before;
    for (int i = 0; i < frames; ++i) {
      EXPECT_EQ(world->step(dt), Status::Ok);
      for (const ContactEvent& e : world->contactEvents())
        if (e.colliderIndex1 == box.index1 && e.colliderGeneration == box.generation)
          ++(e.type == ContactEvent::Type::Begin ? rest.begins : rest.ends);
      const Vec3 now = world->collider(box)->pose().position;
      if (i == frames - lastHalfSecond - 1) halfSecondAgo = now;
      if (i >= frames - lastHalfSecond) rest.fastest = std::max(rest.fastest, (now - before).norm() / dt);
      before = now;
    }
    const Vec3 end = world->collider(box)->pose().position;
    rest.frames = frames;
    rest.drift = (end - halfSecondAgo).norm();
    rest.readSpeed = world->collider(box)->linearVelocity().norm();
    rest.gap = end.y() - half.y() - highestY(*world->deformable(jelly));
    return rest;
  }
};

// A 2 kg box dropped from 0.3 m onto the pinned jelly: the jelly stops it and carries it, the
// box at rest on its top (the box's velocities are unknowns of the jelly's solve, so its light
// mass cannot bounce off the jelly's stiffness). A 0.3 m box rests on the top's nine middle
// nodes.
TEST(DeformablePushesRigid, ABoxDroppedOnAPinnedJellyIsStopped) {
  BoxOnPinnedJelly scene(2.0, 0.15, 0.3);
  const BoxOnPinnedJelly::Rest rest = scene.run(180);
  rest.print("0.3 m box");
  rest.expectAtRest();
  // What a host reads is the velocity it moved with (the jelly's push waits for the next step).
  EXPECT_LT(rest.readSpeed, 0.01);
  // The contacts solved with the box report its touching like any collider's: it landed and stayed.
  EXPECT_GE(rest.begins, 1);
  EXPECT_EQ(rest.begins, rest.ends + 1);
}

// A 0.2 m box has its edges right over the top nodes at ±0.1 m. The nodes beside its edges touch
// them with a normal that turns a right angle over a fraction of a millimetre; its corners on
// the triangles hold it (docs/choices.md, "Contacts", has the figures).
TEST(DeformablePushesRigid, ABoxWhoseEdgesLieOverNodesRests) {
  BoxOnPinnedJelly scene(2.0, 0.1, 0.3);
  const BoxOnPinnedJelly::Rest rest = scene.run(300);
  rest.print("0.2 m box");
  rest.expectAtRest();
}

// A box smaller than the jelly's elements (0.08 m on nodes 0.1 m apart), dropped between the top
// nodes: no node lies under it, and its corners on the top's triangles carry it (without them it
// fell through the jelly to the ground).
TEST(DeformablePushesRigid, ABoxSmallerThanTheElementsRestsOnTheTrianglesByItsCorners) {
  BoxOnPinnedJelly scene(2.0, 0.04, 0.3, 0.05);
  const BoxOnPinnedJelly::Rest rest = scene.run(180);
  rest.print("0.08 m box");
  rest.expectAtRest();
}

// A 10 kg 0.2 m box dropped between the top nodes of the soft jelly (E = 2e4, 19 kg) near its
// corner: it rocks, tips towards the corner it overhangs and comes to rest in the dent it presses
// (without its corners on the triangles it sank through the jelly to the ground). The dent is
// within twice what a level box's would be if the column under it alone carried its weight at
// the uniaxial strain (weight / area) / E over the jelly's 0.4 m: the tilt over the corner
// deepens it.
TEST(DeformablePushesRigid, AHeavyBoxRestsInTheDentItPresses) {
  const double mass = 10.0, halfWidth = 0.1;
  BoxOnPinnedJelly scene(mass, halfWidth, 0.3, 0.05);
  const BoxOnPinnedJelly::Rest rest = scene.run(600);
  rest.print("10 kg 0.2 m box");
  EXPECT_LT(rest.fastest, 0.05);
  EXPECT_LT(rest.drift, 1e-3);
  const double uniaxialSink = mass * 9.81 / (4.0 * halfWidth * halfWidth) / 2e4 * 0.4;
  const double centre = scene.world->collider(scene.box)->pose().position.y();
  std::printf("its centre %.4f m high, %.4f m below where a level box's would be on the jelly's top\n", centre,
              0.4 + scene.half.y() - centre);
  EXPECT_GT(centre, 0.4 + scene.half.y() - 2.0 * uniaxialSink);
}

// A 1 kg sphere of 4 cm radius dropped between the top nodes (nodes 0.1 m apart): a round body
// has no corners, so each triangle near it takes the sphere's point deepest under the
// triangle's plane instead; the sphere lands on the jelly's top (without those points it fell
// through the jelly to the ground within a quarter second). Over its first second it stays on
// the top; later it rolls off (docs/choices.md, "Contacts": the dent of linear elements under it
// is the triangle it sits on, tilted towards its most loaded node).
TEST(DeformablePushesRigid, ASmallSphereLandsOnTheJellyBetweenItsNodes) {
  BoxOnPinnedJelly scene(1.0, 0.04, 0.3, 0.05);
  ASSERT_EQ(scene.world->destroyCollider(scene.box), Status::Ok);
  ColliderDesc sphere = dynamicBox(Vec3::Zero(), 1.0, Vec3(0.05, 0.4 + 0.3 + 0.04, 0.05));
  sphere.shape.type = ShapeType::Sphere;
  sphere.shape.radius = 0.04;
  ASSERT_EQ(scene.world->createCollider(sphere, &scene.box), Status::Ok) << lastError();
  double lowest = 1e30;
  for (int i = 0; i < 60; ++i) {
    ASSERT_EQ(scene.world->step(1.0 / 60.0), Status::Ok);
    lowest = std::min(lowest, scene.world->collider(scene.box)->pose().position.y());
  }
  const double bottom = lowest - 0.04, end = scene.world->collider(scene.box)->pose().position.y() - 0.04;
  std::printf("small sphere: its bottom at most %.4f m deep in the impact's dent, %.4f m after a second (the jelly's "
              "top at 0.4 m)\n", 0.4 - bottom, 0.4 - end);
  EXPECT_GT(bottom, 0.2);     // the impact's dent, not through the jelly
  EXPECT_NEAR(end, 0.4, 0.02);  // back on the top, in the dent its weight presses
  EXPECT_LT(std::abs(scene.world->collider(scene.box)->linearVelocity().y()), 0.1);
}

// Attachments to a dynamic body pull both ways. A box of 0.5, 2 or 10 kg hangs from a jelly
// pinned at its top, its top face attached to the jelly's bottom nodes: the box comes to rest,
// the attachments carry its weight and the nodes stay on the box.
void expectHangingBoxComesToRest(double mass) {
  SCOPED_TRACE(mass);
  std::unique_ptr<World> world = testutil::unbudgetedWorld();
  DeformableHandle jelly;
  ASSERT_EQ(world->createDeformable(jellyCube(Vec3(-0.2, 0.0, -0.2), 300.0), &jelly), Status::Ok) << lastError();
  DeformableBody& body = *world->deformable(jelly);
  std::vector<int32_t> top, bottom;
  for (int32_t i = 0; i < body.nodeCount(); ++i) {
    if (body.positions()[3 * i + 1] > 0.4 - 1e-9) top.push_back(i);
    if (body.positions()[3 * i + 1] < 1e-9) bottom.push_back(i);
  }
  ASSERT_EQ(body.setPinned(top.data(), static_cast<int64_t>(top.size()), true), Status::Ok);
  const Vec3 half(0.2, 0.05, 0.2);
  ColliderHandle box;
  ASSERT_EQ(world->createCollider(dynamicBox(half, mass, Vec3(0, -half.y(), 0)), &box), Status::Ok) << lastError();
  ASSERT_EQ(body.attach(bottom.data(), static_cast<int64_t>(bottom.size()), box.index1, box.generation,
                        *world->collider(box)),
            Status::Ok)
      << lastError();
  const double dt = 1.0 / 60.0;
  const int frames = 180, lastSecond = 60;
  double pull = 0.0, fastest = 0.0;
  Vec3 before = world->collider(box)->pose().position;
  for (int i = 0; i < frames; ++i) {
    ASSERT_EQ(world->step(dt), Status::Ok);
    const Vec3 now = world->collider(box)->pose().position;
    if (i >= frames - lastSecond) {
      for (const ContactReaction& r : body.contactReactions()) pull += r.impulse.y();
      fastest = std::max(fastest, (now - before).norm() / dt);
    }
    before = now;
  }
  // The attached nodes where the box carries them: at rest, on its top face, where they began.
  const Collider& c = *world->collider(box);
  double off = 0.0;
  for (int32_t n : bottom) {
    const Vec3 x(body.positions()[3 * n], body.positions()[3 * n + 1], body.positions()[3 * n + 2]);
    const Vec3 rest(body.restPositions()[3 * n], half.y(), body.restPositions()[3 * n + 2]);
    off = std::max(off, (x - c.pose().apply(rest)).norm());
  }
  const double meanPull = pull / (lastSecond * dt);
  std::printf("%.1f kg box hanging from a jelly: over the last second the attachments pulled %.3f N (its weight %.3f N), "
              "its speed at most %.4f m/s; it hangs %.4f m below where it started, the nodes within %.1e m of its "
              "top\n",
              mass, meanPull, mass * 9.81, fastest, -c.pose().position.y() - half.y(), off);
  EXPECT_NEAR(meanPull, mass * 9.81, 0.02 * mass * 9.81);
  EXPECT_LT(fastest, 0.01);
  EXPECT_LT(off, 1e-3);
  EXPECT_GT(c.pose().position.y(), -half.y() - 0.05);  // held up: it sagged, did not fall away
}

TEST(DeformablePushesRigid, ABoxHangingFromAPinnedJellyByAttachmentsComesToRest) {
  for (double mass : {0.5, 2.0, 10.0}) expectHangingBoxComesToRest(mass);
}

// In zero gravity a jelly at 1 m/s drags the 1 kg ball attached to it: the two move on together
// and the momentum is kept.
TEST(DeformablePushesRigid, AJellyDragsTheBallAttachedToItAndKeepsTheMomentum) {
  ZeroGravityScene s;
  ASSERT_EQ(s.world->step(1.0 / 60.0), Status::Ok);  // the jelly is still 0.2 m off the ball
  DeformableBody& body = *s.world->deformable(s.jelly);
  std::vector<double> slow(body.velocities().size(), 0.0);
  for (size_t k = 0; k < slow.size(); k += 3) slow[k] = 1.0;
  ASSERT_EQ(body.setVelocities(slow.data(), static_cast<int64_t>(slow.size())), Status::Ok);
  // Its nodes on the face towards the ball, attached to it where they are.
  std::vector<int32_t> face;
  double front = -1e30;
  for (int32_t i = 0; i < body.nodeCount(); ++i) front = std::max(front, body.positions()[3 * i]);
  for (int32_t i = 0; i < body.nodeCount(); ++i)
    if (body.positions()[3 * i] > front - 1e-9) face.push_back(i);
  ASSERT_EQ(body.attach(face.data(), static_cast<int64_t>(face.size()), s.ball.index1, s.ball.generation,
                        *s.world->collider(s.ball)),
            Status::Ok);
  const Vec3 before = s.jellyMomentum() + s.ballMomentum();
  for (int i = 0; i < 60; ++i) ASSERT_EQ(s.world->step(1.0 / 60.0), Status::Ok);
  const Vec3 ball = s.ballMomentum() / s.ballMass;
  const Vec3 after = s.jellyMomentum() + s.ballMomentum();
  const double common = before.x() / (s.jellyMass() + s.ballMass);
  std::printf("jelly drags a ball: the ball at %.4f m/s, the common speed %.4f; momentum %.4f -> %.4f (%.1e)\n",
              ball.x(), common, before.x(), after.x(), (after - before).norm() / before.norm());
  // Bullet keeps the ball's velocity in single precision (6e-8 relative), and the load changes
  // it twice a frame.
  EXPECT_LT((after - before).norm(), 1e-4 * before.norm());
  EXPECT_NEAR(ball.x(), common, 0.05 * common);
}

// The jelly and the box solve as one system: the same bits for any worker count.
TEST(DeformablePushesRigid, TheirOneSolveIsBitwiseEqualForAnyWorkerCount) {
  auto run = [](int workers) {
    BoxOnPinnedJelly scene(2.0, 0.15, 0.1, 0.0, workers);
    for (int i = 0; i < 40; ++i) EXPECT_EQ(scene.world->step(1.0 / 60.0), Status::Ok);
    const DeformableBody& body = *scene.world->deformable(scene.jelly);
    std::vector<double> state(body.positions().begin(), body.positions().end());
    state.insert(state.end(), body.velocities().begin(), body.velocities().end());
    const Collider& c = *scene.world->collider(scene.box);
    for (const Vec3& v : {c.pose().position, c.linearVelocity(), c.angularVelocity()})
      state.insert(state.end(), v.data(), v.data() + 3);
    return state;
  };
  const std::vector<double> one = run(1);
  for (int workers : {2, 3}) {
    const std::vector<double> other = run(workers);
    ASSERT_EQ(one.size(), other.size());
    EXPECT_EQ(std::memcmp(one.data(), other.data(), one.size() * sizeof(double)), 0) << workers << " workers";
  }
}

}  // namespace
}  // namespace vp

// Deformable contacts against Bullet colliders, inside the implicit solve.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/box_tet_mesh.h"
#include "world.h"

namespace vp {
namespace {

struct Scene {
  std::unique_ptr<World> world;
  DeformableHandle cube{};

  explicit Scene(double gravityAngleDeg = 0.0) {
    WorldConfig config;
    config.workerCount = 2;
    config.frameBudgetMs = 0.0;  // tests: no budget cuts
    // An incline is modelled by tilting gravity: the plane stays y = 0, so the geometry is
    // exact and the slope angle is exactly the gravity angle.
    const double a = gravityAngleDeg * M_PI / 180.0;
    config.gravity = 9.81 * Vec3(std::sin(a), -std::cos(a), 0.0);
    EXPECT_EQ(World::create(config, &world), Status::Ok);
  }
  ColliderHandle addCollider(ColliderDesc d) {
    ColliderHandle h;
    EXPECT_EQ(world->createCollider(std::move(d), &h), Status::Ok) << lastError();
    return h;
  }
  ColliderHandle addGround(double friction = 1.0) {
    ColliderDesc g;
    g.shape.type = ShapeType::Plane;
    g.friction = friction;
    return addCollider(g);
  }
  DeformableBody& addCube(double size, const Vec3& centre, double friction, double E = 1e5, int degree = 1) {
    DeformableDesc d;
    d.degree = degree;
    d.mesh = makeBoxTetMesh({3, 3, 3}, Vec3::Constant(size), -0.5 * Vec3::Constant(size));
    d.pose.position = centre;
    d.material.youngsModulus = E;
    d.material.friction = friction;
    d.material.stiffnessDamping = 0.02;
    d.solver.tolerance = 1e-6;
    d.solver.maxIterations = 500;
    EXPECT_EQ(world->createDeformable(std::move(d), &cube), Status::Ok) << lastError();
    return *world->deformable(cube);
  }
  DeformableBody& body() { return *world->deformable(cube); }
  void run(int steps) {
    for (int i = 0; i < steps; ++i) ASSERT_EQ(world->step(1.0 / 60.0), Status::Ok);
  }
  double minY() {
    double m = 1e9;
    for (int32_t i = 0; i < body().nodeCount(); ++i) m = std::min(m, body().positions()[3 * i + 1]);
    return m;
  }
  Vec3 centroidVelocity() {
    Vec3 v = Vec3::Zero();
    for (int32_t i = 0; i < body().nodeCount(); ++i)
      v += Vec3(body().velocities()[3 * i], body().velocities()[3 * i + 1], body().velocities()[3 * i + 2]);
    return v / body().nodeCount();
  }
  Vec3 centroid() {
    Vec3 c = Vec3::Zero();
    for (int32_t i = 0; i < body().nodeCount(); ++i)
      c += Vec3(body().positions()[3 * i], body().positions()[3 * i + 1], body().positions()[3 * i + 2]);
    return c / body().nodeCount();
  }
};

TEST(DeformableContact, CubeComesToRestOnAPlaneWithoutPenetrationOrJitter) {
  Scene s;
  s.addGround();
  s.addCube(0.5, Vec3(0, 1.0, 0), 0.5);
  s.run(180);
  // Penetration below 1% of the cube's size, and at rest.
  EXPECT_GT(s.minY(), -0.01 * 0.5);
  EXPECT_LT(s.minY(), 0.01 * 0.5);  // and actually down on the plane
  EXPECT_LT(s.centroidVelocity().norm(), 1e-3);
  // No jitter: another second of resting changes nothing visible.
  const Vec3 before = s.centroid();
  s.run(60);
  EXPECT_LT((s.centroid() - before).norm(), 1e-4);
  EXPECT_GT(s.body().contacts().size(), 0u);
}

// Higher-order cubes collide through their vertex and boundary control points.
TEST(DeformableContact, QuadraticAndCubicCubesRestOnAPlane) {
  for (int degree : {2, 3}) {
    Scene s;
    s.addGround();
    s.addCube(0.5, Vec3(0, 0.6, 0), 0.5, 1e5, degree);
    s.run(150);
    EXPECT_GT(s.minY(), -0.005) << "degree " << degree;
    EXPECT_LT(s.minY(), 0.005) << "degree " << degree;
    EXPECT_LT(s.centroidVelocity().norm(), 1e-3) << "degree " << degree;
    // The render mesh (the box surface, evaluated through the BB polynomial) sits on the plane.
    double renderMinY = 1e9;
    for (const Vec3& p : s.body().renderPositions()) renderMinY = std::min(renderMinY, p.y());
    EXPECT_NEAR(renderMinY, 0.0, 0.01) << "degree " << degree;
  }
}

// On an incline of angle θ with friction μ: sticks when tan θ < μ, slides otherwise.
struct InclineRun {
  double distance;      // along the slope in the measured second
  double acceleration;  // along the slope, from the centroid velocity change
};

InclineRun runIncline(double angleDeg, double friction) {
  Scene s(angleDeg);
  s.addGround(1.0);  // combined μ = body friction × 1
  s.addCube(0.5, Vec3(0, 0.25 + 0.002, 0), friction, 1e6);
  s.run(30);  // settle onto the plane
  const double x0 = s.centroid().x(), v0 = s.centroidVelocity().x();
  s.run(60);
  return InclineRun{s.centroid().x() - x0, s.centroidVelocity().x() - v0};
}

TEST(DeformableContact, SticksOnAnInclineBelowTheFrictionAngleAndSlidesAbove) {
  const double mu = 0.5;  // friction angle atan(0.5) = 26.6 degrees
  const InclineRun stick = runIncline(20.0, mu);
  const InclineRun slide = runIncline(33.0, mu);
  EXPECT_LT(std::abs(stick.distance), 5e-3) << "crept " << stick.distance << " m in 1 s at 20 degrees";
  // Sliding: Coulomb's kinetic friction gives a = g (sin θ − μ cos θ) = 1.23 m/s². The cube
  // is elastic and its contacts switch between stick and slip at the start, so allow 10%.
  const double theta = 33.0 * M_PI / 180.0;
  const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  EXPECT_NEAR(slide.acceleration, expected, 0.1 * expected);
  EXPECT_GT(slide.distance, 0.3);
}

TEST(DeformableContact, KinematicPaddlePushesTheCube) {
  Scene s;
  s.addGround(0.3);
  s.addCube(0.5, Vec3(0, 0.25 + 0.002, 0), 0.3);
  ColliderDesc paddle;
  paddle.bodyType = BodyType::Kinematic;
  paddle.shape.type = ShapeType::Box;
  paddle.shape.halfExtents = Vec3(0.05, 0.3, 0.6);
  paddle.pose.position = Vec3(-0.6, 0.3, 0);
  paddle.linearVelocity = Vec3(1.0, 0, 0);
  ColliderHandle h = s.addCollider(paddle);
  s.run(60);  // the paddle travels 1 m: it meets the cube after ~0.3 s and pushes it
  const double paddleFront = s.world->collider(h)->pose().position.x() + 0.05;
  double minX = 1e9;
  for (int32_t i = 0; i < s.body().nodeCount(); ++i) minX = std::min(minX, s.body().positions()[3 * i]);
  EXPECT_GT(s.centroid().x(), 0.4);          // it moved...
  EXPECT_GT(minX, paddleFront - 0.01);      // ...in front of the paddle, not through it
  EXPECT_GT(s.minY(), -0.005);
}

// Dynamic colliders are contact geometry too (their pose is synced after each rigid step).
// Coupling is one-way: the box is heavy enough that ignoring the cube's weight on it is moot.
TEST(DeformableContact, HeldUpByADynamicBodyRestingOnTheGround) {
  Scene s;
  s.addGround();
  ColliderDesc box;
  box.bodyType = BodyType::Dynamic;
  box.mass = 500.0;
  box.shape.type = ShapeType::Box;
  box.shape.halfExtents = Vec3(0.6, 0.2, 0.6);
  box.pose.position = Vec3(0, 0.25, 0);  // drops 5 cm onto the plane, then rests
  ColliderHandle h = s.addCollider(box);
  s.addCube(0.3, Vec3(0, 0.9, 0), 0.8);
  s.run(120);
  const double boxTop = s.world->collider(h)->pose().position.y() + 0.2;
  EXPECT_NEAR(boxTop, 0.4, 0.01);
  EXPECT_GT(s.minY(), boxTop - 0.005);
  EXPECT_LT(s.minY(), boxTop + 0.01);
}

// The multigrid preconditioners restrict every level to the constrained space, so they must
// follow the contact set when an active-set pass changes it (a contact released or set
// sliding). Stale ones had no correction for the nodes a pass set free, and CG stalled at a
// relative residual near 1 from the first landing on. A tilted cube lands on a corner and
// tips over onto a face, so its contacts keep changing.
TEST(DeformableContact, MultigridSolvesConvergeWhileContactsChange) {
  struct Case {
    int degree, cells;
    Preconditioner preconditioner;
    PMultigridCoarseOperator coarse;
    const char* name;
  };
  const Case cases[] = {
      {1, 7, Preconditioner::Multigrid, PMultigridCoarseOperator::Galerkin, "linear, aggregation multigrid"},
      {3, 3, Preconditioner::PMultigrid, PMultigridCoarseOperator::Galerkin, "cubic, p-multigrid (Galerkin)"},
      {3, 3, Preconditioner::PMultigrid, PMultigridCoarseOperator::Rediscretized, "cubic, p-multigrid (re-discretized)"},
  };
  for (const Case& c : cases) {
    Scene s;
    s.addGround(0.5);
    DeformableDesc d;
    d.degree = c.degree;
    d.mesh = makeBoxTetMesh({c.cells, c.cells, c.cells}, Vec3::Constant(0.5), Vec3::Constant(-0.25));
    d.pose.position = Vec3(0, 0.45, 0);
    d.pose.rotation = Quat(Eigen::AngleAxisd(0.6, Vec3(0, 0, 1))) * Quat(Eigen::AngleAxisd(0.35, Vec3(1, 0, 0)));
    d.material.youngsModulus = 1e5;
    d.solver.tolerance = 1e-6;
    d.solver.maxIterations = 500;
    d.solver.preconditioner = c.preconditioner;
    d.solver.pMultigridCoarseOperator = c.coarse;
    ASSERT_EQ(s.world->createDeformable(std::move(d), &s.cube), Status::Ok) << lastError();
    ASSERT_EQ(s.body().preconditioner(), c.preconditioner) << c.name;
    int contactSteps = 0;
    for (int step = 0; step < 45; ++step) {
      ASSERT_EQ(s.world->step(1.0 / 60.0), Status::Ok);
      const PhaseStats& solve = s.world->lastStats().actors.at(1).phase(Phase::Solve);
      EXPECT_LE(solve.residual, 1e-6) << c.name << ", step " << step << " (" << s.body().contacts().size()
                                      << " contacts, " << solve.iterations << " iterations)";
      contactSteps += !s.body().contacts().empty();
    }
    EXPECT_GT(contactSteps, 20) << c.name;
  }
}

class DeformableContactShapes : public ::testing::TestWithParam<ShapeType> {};

// A soft cube dropped on each kind of collider is held up by it.
TEST_P(DeformableContactShapes, CubeIsHeldUpByTheCollider) {
  Scene s;
  ColliderDesc c;
  c.shape.type = GetParam();
  c.shape.radius = 0.6;
  c.shape.halfHeight = 0.3;
  c.shape.halfExtents = Vec3(0.8, 0.4, 0.8);
  double top = 0.4;
  switch (GetParam()) {
    case ShapeType::Sphere: top = 0.6; break;
    case ShapeType::Capsule: top = 0.9; break;
    case ShapeType::Cylinder: top = 0.3; break;
    case ShapeType::ConvexHull:
      c.shape.points = {Vec3(-1, -0.4, -1), Vec3(1, -0.4, -1), Vec3(-1, -0.4, 1), Vec3(1, -0.4, 1),
                        Vec3(-1, 0.4, -1), Vec3(1, 0.4, -1), Vec3(-1, 0.4, 1), Vec3(1, 0.4, 1)};
      break;
    case ShapeType::TriangleMesh: {
      // A closed box as triangles.
      for (int i = 0; i < 8; ++i) c.shape.points.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 0.4 : -0.4, i & 4 ? 1 : -1));
      c.shape.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                           {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
      break;
    }
    default: break;
  }
  ColliderHandle h = s.addCollider(c);
  s.addCube(0.3, Vec3(0, top + 0.3, 0), 0.8);
  s.run(120);
  // Held up: no node is inside the collider by more than 1% of the cube's size, and the
  // cube rests on it rather than having slid off (its centre is still above the top).
  const PreparedCollider* geometry = s.world->collider(h)->geometry();
  ASSERT_NE(geometry, nullptr);
  double deepest = 1e9;
  for (int32_t i = 0; i < s.body().nodeCount(); ++i)
    deepest = std::min(deepest, signedDistanceBound(*geometry, Vec3(s.body().positions()[3 * i],
                                                                    s.body().positions()[3 * i + 1],
                                                                    s.body().positions()[3 * i + 2])));
  EXPECT_GT(deepest, -0.003) << shapeTypeName(GetParam());
  EXPECT_LT(deepest, 0.01) << shapeTypeName(GetParam()) << ": not touching";
  EXPECT_GT(s.centroid().y(), top) << shapeTypeName(GetParam());
}

INSTANTIATE_TEST_SUITE_P(AllShapes, DeformableContactShapes,
                         ::testing::Values(ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule, ShapeType::Cylinder,
                                           ShapeType::ConvexHull, ShapeType::TriangleMesh),
                         [](const auto& testParam) { return std::string(shapeTypeName(testParam.param)); });

}  // namespace
}  // namespace vp

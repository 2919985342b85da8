// Box, half-space plane and convex hull face coverage (exact clipping paths).
// Hand-computed areas: tolerance 1e-12 (round-off). Against supersampling on an n x n midpoint
// grid: tolerance 1e-3 of the face area as required; the sampling error itself is about
// sqrt(#boundary samples)/n^2 (~1e-5 at n = 2000) so this leaves the path's own error visible.
#include "collide/face_coverage.h"
#include "fluid_face_test_util.h"
#include "random_values.h"

#include <gtest/gtest.h>

#include <limits>

namespace vp {
namespace {

constexpr double kPi = 3.14159265358979323846;

ColliderShape box(const Eigen::Vector3d& he, const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
  ColliderShape s;
  s.kind = ShapeKind::Box;
  s.halfExtents = he;
  s.rotation = q;
  s.translation = t;
  return s;
}

TEST(FluidFaceBox, RotatedAboutFaceNormalSquareInside) {
  // Box long along z, rotated 45 deg about z: cross-section is a 0.6 x 0.6 square rotated
  // in-plane, vertices at 0.424 < 0.5 from the centre -> area 0.36.
  const Eigen::Quaterniond q(Eigen::AngleAxisd(kPi / 4, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(coveredFraction(box({0.3, 0.3, 5}, q, {0, 0, 0}), testutil::unitFace(2)), 0.36, 1e-12);
}

TEST(FluidFaceBox, RotatedAboutFaceNormalOctagon) {
  // Unit square rotated 45 deg over the unit face: regular octagon of area 2 (sqrt 2 - 1).
  const Eigen::Quaterniond q(Eigen::AngleAxisd(kPi / 4, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(coveredFraction(box({0.5, 0.5, 5}, q, {0, 0, 0}), testutil::unitFace(2)),
              2.0 * (std::sqrt(2.0) - 1.0), 1e-12);
  // Same on axis-0 and axis-1 faces (rotation about that axis).
  const Eigen::Quaterniond qx(Eigen::AngleAxisd(kPi / 4, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(coveredFraction(box({5, 0.5, 0.5}, qx, {0, 0, 0}), testutil::unitFace(0)),
              2.0 * (std::sqrt(2.0) - 1.0), 1e-12);
}

TEST(FluidFaceBox, TiltedSlabWidthGrowsAsOneOverCos) {
  // Slab of half-thickness a (local x) tilted by theta about y: in the plane z = 0 it is a band
  // |x| <= a / cos(theta), full height in y.
  for (double theta : {0.0, 0.3, 0.7, 1.1}) {
    const double a = 0.2;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()));
    const double expected = std::min(1.0, 2 * a / std::cos(theta));
    EXPECT_NEAR(coveredFraction(box({a, 5, 5}, q, {0, 0, 0}), testutil::unitFace(2)), expected,
                1e-12) << "theta " << theta;
  }
}

TEST(FluidFaceBox, AxisAlignedCornerAndOutside) {
  const Eigen::Quaterniond id = Eigen::Quaterniond::Identity();
  EXPECT_NEAR(coveredFraction(box({0.5, 0.5, 0.5}, id, {0.5, 0.5, 0.2}), testutil::unitFace(2)),
              0.25, 1e-12);
  EXPECT_EQ(coveredFraction(box({0.5, 0.5, 0.5}, id, {0, 0, 0.7}), testutil::unitFace(2)), 0.0);
  EXPECT_EQ(coveredFraction(box({2, 2, 2}, id, {0, 0, 0}), testutil::unitFace(1)), 1.0);
}

TEST(FluidFaceBox, RandomPosesAgainstSupersampling2000) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.6, 0.6), e(0.15, 0.7);
  double maxErr = 0.0;
  int partial = 0;
  for (int t = 0; t < 4; ++t) {
    const Eigen::Vector3d halfExtents = testing_values::randomVector(e, rng);
    const Eigen::Quaterniond rotation = testutil::randomRotation(rng);
    const ColliderShape s = box(halfExtents, rotation, testing_values::randomVector(u, rng));
    const AxisFace f = testutil::unitFace(t % 3);
    const double got = coveredFraction(s, f);
    const double ref = testutil::supersample(f, 2000, [&](const Eigen::Vector3d& x) {
      return testutil::insideWorld(s, x);
    });
    maxErr = std::max(maxErr, std::fabs(got - ref));
    partial += (ref > 0.02 && ref < 0.98) ? 1 : 0;
    EXPECT_NEAR(got, ref, 1e-3) << "trial " << t;
  }
  EXPECT_GE(partial, 2);
  std::printf("box vs supersampling(2000^2): max error %.3g\n", maxErr);
}

// The sub-step rule's speed bound: a moving plane's speed, not NaN from its infinite extent.
TEST(FluidFacePlane, AMovingPlaneBoundsItsSpeedByItsVelocity) {
  ColliderShape s;
  s.kind = ShapeKind::Plane;
  s.planeNormal = Eigen::Vector3d(0, 1, 0);
  s.linearVelocity = Eigen::Vector3d(0, 3, 0);
  PreparedCollider c;
  ASSERT_EQ(prepareCollider(s, &c), Status::Ok);
  EXPECT_EQ(solidSpeedBound(c), 3.0);
  s.linearVelocity.setZero();
  ASSERT_EQ(prepareCollider(s, &c), Status::Ok);
  EXPECT_EQ(solidSpeedBound(c), 0.0);
  s.angularVelocity = Eigen::Vector3d(0, 1, 0);  // a spinning plane has no finite bound
  ASSERT_EQ(prepareCollider(s, &c), Status::Ok);
  EXPECT_EQ(solidSpeedBound(c), std::numeric_limits<double>::infinity());
}

TEST(FluidFacePlane, AnalyticAndRandom) {
  ColliderShape s;
  s.kind = ShapeKind::Plane;
  s.planeNormal = Eigen::Vector3d(1, 1, 0);  // solid x + y <= 0: half the face (diagonal)
  s.planeOffset = 0.0;
  EXPECT_NEAR(coveredFraction(s, testutil::unitFace(2)), 0.5, 1e-12);
  s.planeNormal = Eigen::Vector3d(0, 0, 1);  // parallel to the face: all or nothing
  EXPECT_EQ(coveredFraction(s, testutil::unitFace(2, {0, 0, -0.1})), 1.0);
  EXPECT_EQ(coveredFraction(s, testutil::unitFace(2, {0, 0, 0.1})), 0.0);
  s.planeNormal = Eigen::Vector3d(1, 0, 0);  // x <= 0.25 -> 0.75
  s.planeOffset = 0.25;
  EXPECT_NEAR(coveredFraction(s, testutil::unitFace(2)), 0.75, 1e-12);

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  double maxErr = 0.0;
  for (int t = 0; t < 6; ++t) {
    ColliderShape p;
    p.kind = ShapeKind::Plane;
    p.planeNormal = testing_values::randomVector(u, rng);
    p.planeOffset = 0.5 * u(rng);
    p.rotation = testutil::randomRotation(rng);
    p.translation = testing_values::randomVector(u, rng) * 0.3;
    const AxisFace f = testutil::unitFace(t % 3);
    const double got = coveredFraction(p, f);
    const double ref = testutil::supersample(f, 800, [&](const Eigen::Vector3d& x) {
      return testutil::insideWorld(p, x);
    });
    maxErr = std::max(maxErr, std::fabs(got - ref));
    EXPECT_NEAR(got, ref, 1e-3) << "trial " << t;
  }
  std::printf("plane vs supersampling(800^2): max error %.3g\n", maxErr);
}

TEST(FluidFaceHull, OctahedronRandomPoses) {
  ColliderShape s;
  s.kind = ShapeKind::ConvexHull;
  const double r = 0.7;
  for (int a = 0; a < 3; ++a)
    for (double sgn : {-1.0, 1.0}) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      p[a] = sgn * r;
      s.hullPoints.push_back(p);
    }
  s.hullPoints.push_back(Eigen::Vector3d(0.1, 0.1, 0.1));  // interior point, must be ignored
  // Axis-aligned, face through the centre: the cross-section |x| + |y| <= r is a diamond of
  // area 2 r^2 = 0.98, clipped by the unit square: corners beyond 0.5 by 0.2 -> 4 * 0.04.
  EXPECT_NEAR(coveredFraction(s, testutil::unitFace(2)), 2 * r * r - 4 * 0.2 * 0.2, 1e-12);

  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  double maxErr = 0.0;
  int partial = 0;
  for (int t = 0; t < 6; ++t) {
    s.rotation = testutil::randomRotation(rng);
    s.translation = testing_values::randomVector(u, rng);
    const Eigen::Quaterniond qi = s.rotation.conjugate();
    const AxisFace f = testutil::unitFace(t % 3);
    const double got = coveredFraction(s, f);
    const double ref = testutil::supersample(f, 800, [&](const Eigen::Vector3d& x) {
      return (qi * (x - s.translation)).cwiseAbs().sum() <= r;
    });
    maxErr = std::max(maxErr, std::fabs(got - ref));
    partial += (ref > 0.02 && ref < 0.98) ? 1 : 0;
    EXPECT_NEAR(got, ref, 1e-3) << "trial " << t;
  }
  EXPECT_GE(partial, 3);
  std::printf("octahedron hull vs supersampling(800^2): max error %.3g\n", maxErr);
}

TEST(FluidFaceHull, RandomHullOfCubeCornersPlusInteriorEqualsBox) {
  // Hull of a box's corners plus random interior points is the box: both exact paths agree.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d he(0.4, 0.3, 0.6);
  ColliderShape hull;
  hull.kind = ShapeKind::ConvexHull;
  for (int c = 0; c < 8; ++c)
    hull.hullPoints.push_back(Eigen::Vector3d(c & 1 ? he.x() : -he.x(), c & 2 ? he.y() : -he.y(),
                                              c & 4 ? he.z() : -he.z()));
  for (int i = 0; i < 200; ++i)
    hull.hullPoints.push_back(0.999 * he.cwiseProduct(testing_values::randomVector(u, rng)));
  std::shuffle(hull.hullPoints.begin(), hull.hullPoints.end(), rng);
  PreparedCollider ph;
  ASSERT_EQ(prepareCollider(hull, &ph), Status::Ok) << lastError();
  EXPECT_EQ(ph.localPlanes.size(), 6u);
  for (int t = 0; t < 20; ++t) {
    const Eigen::Quaterniond q = testutil::randomRotation(rng);
    const Eigen::Vector3d tr = 0.5 * testing_values::randomVector(u, rng);
    ASSERT_EQ(setColliderPose(&ph, q, tr), Status::Ok);
    ColliderShape b = box(he, q, tr);
    const AxisFace f = testutil::unitFace(t % 3, Eigen::Vector3d::Zero(), 0.7);
    EXPECT_NEAR(coveredFraction(ph, f), coveredFraction(b, f), 1e-12) << "trial " << t;
  }
}

TEST(FluidFaceHull, RandomPointCloudHullContainsAllPointsAndIsTight) {
  std::mt19937 rng(21);
  std::normal_distribution<double> g(0.0, 1.0);
  ColliderShape hull;
  hull.kind = ShapeKind::ConvexHull;
  for (int i = 0; i < 60; ++i) hull.hullPoints.push_back(testing_values::randomVector(g, rng));
  PreparedCollider ph;
  ASSERT_EQ(prepareCollider(hull, &ph), Status::Ok) << lastError();
  // Every plane supports the hull: all points inside, at least 3 points on it.
  for (const auto& p : ph.localPlanes) {
    int on = 0;
    for (const auto& x : hull.hullPoints) {
      const double d = p.head<3>().dot(x) - p.w();
      EXPECT_LE(d, 1e-9);
      on += std::fabs(d) < 1e-9 ? 1 : 0;
    }
    EXPECT_GE(on, 3);
  }
  // Supersampling with an independent inside test is not available for a point cloud; the
  // clipping path is compared with the plane-based signed distance sign instead.
  const AxisFace f = testutil::unitFace(1, Eigen::Vector3d(0.2, 0.1, -0.3), 1.5);
  const double got = coveredFraction(ph, f);
  const double ref = testutil::supersample(f, 800, [&](const Eigen::Vector3d& x) {
    return signedDistanceBound(ph, x) <= 0.0;
  });
  EXPECT_GT(ref, 0.05);
  EXPECT_NEAR(got, ref, 1e-3);
}

TEST(FluidFaceHull, RejectsDegenerateInput) {
  ColliderShape s;
  s.kind = ShapeKind::ConvexHull;
  s.hullPoints = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};  // coplanar
  PreparedCollider p;
  EXPECT_EQ(prepareCollider(s, &p), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("coplanar"), std::string::npos);
  s.hullPoints.resize(3);
  EXPECT_EQ(prepareCollider(s, &p), Status::InvalidArgument);
  ColliderShape b;
  b.kind = ShapeKind::Box;
  b.halfExtents = Eigen::Vector3d(1, -1, 1);
  EXPECT_EQ(prepareCollider(b, &p), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("halfExtents"), std::string::npos);
}

}  // namespace
}  // namespace vp

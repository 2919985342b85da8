// Capsule and cylinder face coverage (bounded adaptive path, guaranteed error
// <= 0.9e-3 of the face area) against analytic cases and supersampling for random poses.
// The supersampling (800^2 midpoint) error is ~1e-5, so 1e-3 checks the path's own bound.
#include "collide/face_coverage.h"
#include "fluid_face_test_util.h"
#include "random_values.h"

#include <gtest/gtest.h>

namespace vp {
namespace {

constexpr double kPi = 3.14159265358979323846;

ColliderShape round(ShapeKind kind, double r, double hh, const Eigen::Quaterniond& q,
                    const Eigen::Vector3d& t) {
  ColliderShape s;
  s.kind = kind;
  s.radius = r;
  s.halfHeight = hh;
  s.rotation = q;
  s.translation = t;
  return s;
}

TEST(FluidFaceRound, AxisAlignedAnalytic) {
  const Eigen::Quaterniond id = Eigen::Quaterniond::Identity();
  // Cylinder along y cut by a y-face inside its height: disc r = 0.3 -> pi r^2.
  EXPECT_NEAR(coveredFraction(round(ShapeKind::Cylinder, 0.3, 1.0, id, {0, 0, 0}),
                              testutil::unitFace(1)), kPi * 0.09, 1e-3);
  // Cylinder along y cut by a z-face through its axis: rectangle 0.6 x 1 (height clipped).
  EXPECT_NEAR(coveredFraction(round(ShapeKind::Cylinder, 0.3, 1.0, id, {0, 0, 0}),
                              testutil::unitFace(2)), 0.6, 1e-3);
  // Capsule along y, z-face through the axis, segment inside the face: stadium.
  EXPECT_NEAR(coveredFraction(round(ShapeKind::Capsule, 0.1, 0.2, id, {0, 0, 0}),
                              testutil::unitFace(2)), 0.2 * 0.4 + kPi * 0.01, 1e-3);
  // Beyond the cylinder's cap: nothing; capsule's cap sphere slice: disc.
  EXPECT_EQ(coveredFraction(round(ShapeKind::Cylinder, 0.3, 0.5, id, {0, 0, 0}),
                            testutil::unitFace(1, {0, 0.6, 0})), 0.0);
  EXPECT_NEAR(coveredFraction(round(ShapeKind::Capsule, 0.3, 0.5, id, {0, 0, 0}),
                              testutil::unitFace(1, {0, 0.6, 0})), kPi * (0.09 - 0.01), 1e-3);
}

TEST(FluidFaceRound, TiltedCylinderEllipse) {
  // Cylinder tilted by theta about x, cut by the y = 0 face well inside its height: ellipse with
  // semi-axes r and r / cos(theta), area pi r^2 / cos(theta).
  for (double theta : {0.2, 0.6, 0.9}) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitX()));
    const double r = 0.2;
    EXPECT_NEAR(coveredFraction(round(ShapeKind::Cylinder, r, 3.0, q, {0, 0, 0}),
                                testutil::unitFace(1)),
                kPi * r * r / std::cos(theta), 1e-3) << theta;
  }
}

void randomAgainstSupersampling(ShapeKind kind, unsigned seed, const char* name) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.4, 0.4), rr(0.1, 0.5), hh(0.0, 0.6);
  double maxErr = 0.0;
  int partial = 0;
  for (int t = 0; t < 10; ++t) {
    const double radius = rr(rng), halfHeight = kind == ShapeKind::Cylinder ? 0.05 + hh(rng) : hh(rng);
    const Eigen::Quaterniond rotation = testutil::randomRotation(rng);
    const ColliderShape s = round(kind, radius, halfHeight, rotation, testing_values::randomVector(u, rng));
    const AxisFace f = testutil::unitFace(t % 3);
    const double got = coveredFraction(s, f);
    const double ref = testutil::supersample(f, 800, [&](const Eigen::Vector3d& x) {
      return testutil::insideWorld(s, x);
    });
    maxErr = std::max(maxErr, std::fabs(got - ref));
    partial += (ref > 0.02 && ref < 0.98) ? 1 : 0;
    EXPECT_NEAR(got, ref, 1e-3) << name << " trial " << t;
  }
  EXPECT_GE(partial, 4) << name;
  std::printf("%s vs supersampling(800^2): max error %.3g\n", name, maxErr);
}

TEST(FluidFaceRound, CapsuleRandomPoses) { randomAgainstSupersampling(ShapeKind::Capsule, 13, "capsule"); }
TEST(FluidFaceRound, CylinderRandomPoses) { randomAgainstSupersampling(ShapeKind::Cylinder, 17, "cylinder"); }

TEST(FluidFaceRound, TinyContactsAreBounded) {
  // A capsule whose cross-section is a sliver far smaller than the sample spacing: the result
  // must stay within the tolerance of the true (tiny) area.
  const Eigen::Quaterniond id = Eigen::Quaterniond::Identity();
  // Sphere cap of the capsule just crossing the face plane y = 0.5 + hh - 1e-4.
  const ColliderShape s = round(ShapeKind::Capsule, 0.2, 0.3, id, {0.13, 0, -0.21});
  const AxisFace f = testutil::unitFace(1, {0, 0.5 - 1e-4, 0});
  const double rho2 = 0.04 - (0.2 - 1e-4) * (0.2 - 1e-4);
  EXPECT_NEAR(coveredFraction(s, f), kPi * rho2, 1e-3);
  EXPECT_GT(coveredFraction(s, f), 0.0);
}

}  // namespace
}  // namespace vp

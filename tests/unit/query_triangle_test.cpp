// Ray and box tests of one triangle (query/triangle_queries.h) against constructed answers.
#include <gtest/gtest.h>

#include <random>

#include "query/triangle_queries.h"
#include "random_values.h"

namespace vp {
namespace {

Vec3 randomVec(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return testing_values::randomVector(u, rng);
}

TEST(TriangleQueries, ARayAimedAtAKnownPointHitsItWithItsBarycentrics) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 a = randomVec(rng, 1), b = randomVec(rng, 1), c = randomVec(rng, 1);
    double u = unit(rng), v = unit(rng);
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    const Vec3 target = (1 - u - v) * a + u * b + v * c;
    const Vec3 origin = target + randomVec(rng, 3);
    const Vec3 direction = (target - origin).normalized();
    const double distance = (target - origin).norm();
    TriangleRayHit hit;
    ASSERT_TRUE(rayHitsTriangle(origin, direction, 10.0, a, b, c, &hit)) << trial;
    EXPECT_NEAR(hit.distance, distance, 1e-9 * (1 + distance) / std::max(1e-3, std::abs(direction.dot((b - a).cross(c - a).normalized()))));
    // Too short a ray, or one pointing away, misses.
    EXPECT_FALSE(rayHitsTriangle(origin, direction, 0.999 * distance, a, b, c, &hit));
    EXPECT_FALSE(rayHitsTriangle(origin, -direction, 10.0, a, b, c, &hit));
  }
  TriangleRayHit hit;
  ASSERT_TRUE(rayHitsTriangle(Vec3(0.25, 0.25, 5), Vec3(0, 0, -1), 10, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), &hit));
  EXPECT_DOUBLE_EQ(hit.distance, 5.0);
  EXPECT_NEAR(hit.barycentric.x(), 0.5, 1e-15);
  EXPECT_NEAR(hit.barycentric.y(), 0.25, 1e-15);
  EXPECT_NEAR(hit.barycentric.z(), 0.25, 1e-15);
  EXPECT_FALSE(rayHitsTriangle(Vec3(0.6, 0.6, 5), Vec3(0, 0, -1), 10, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), &hit));
}

TEST(TriangleQueries, TriangleBoxOverlapAgreesWithPointsOfTheTriangleInTheBox) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int overlapping = 0, separate = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 a = randomVec(rng, 2), b = randomVec(rng, 2), c = randomVec(rng, 2);
    const Vec3 centre = randomVec(rng, 1), half = Vec3::Constant(0.2) + testing_values::randomVector(unit, rng);
    const Mat3 axes = Quat(Eigen::AngleAxisd(6.3 * unit(rng), randomVec(rng, 1).normalized())).toRotationMatrix();
    bool sampleInside = false;
    for (int i = 0; i <= 60 && !sampleInside; ++i)
      for (int j = 0; i + j <= 60 && !sampleInside; ++j) {
        const Vec3 p = a + (b - a) * (i / 60.0) + (c - a) * (j / 60.0);
        sampleInside = ((axes.transpose() * (p - centre)).cwiseAbs() - half).maxCoeff() <= 0.0;
      }
    const bool sat = triangleOverlapsBox(a, b, c, centre, half, axes);
    // A sampled point of the triangle in the box proves the overlap; the converse cannot be
    // sampled (a sliver may fall between samples), but the counts below show both outcomes.
    if (sampleInside) {
      EXPECT_TRUE(sat) << trial;
    }
    (sat ? overlapping : separate)++;
  }
  EXPECT_GT(overlapping, 50);  // both outcomes were exercised
  EXPECT_GT(separate, 50);
  // A big triangle whose vertices are all outside the box but which cuts through it, and the
  // same moved just past the box's corner along its normal.
  const Mat3 I = Mat3::Identity();
  EXPECT_TRUE(triangleOverlapsBox(Vec3(1.9, 0, -5), Vec3(0, 1.9, -5), Vec3(0.95, 0.95, 5), Vec3::Zero(), Vec3::Ones(), I));
  EXPECT_FALSE(triangleOverlapsBox(Vec3(2.1, 0, -5), Vec3(0, 2.1, -5), Vec3(1.05, 1.05, 5), Vec3::Zero(), Vec3::Ones(), I));
}

}  // namespace
}  // namespace vp

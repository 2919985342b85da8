// RefitBvh against brute force: after a build and after refits to a deformed surface, a box
// visit reaches exactly the triangles whose boxes the box touches, and a ray visit every
// triangle the ray touches (and the closest ray hit is the brute-force one).
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "geometry/refit_bvh.h"
#include "query/triangle_queries.h"
#include "random_values.h"

namespace vp {
namespace {

struct Soup {
  Array<Vec3> x;
  Array<RefitBvh::Triangle> triangles;
};

// Small random triangles scattered in the unit cube.
Soup randomSoup(int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0), e(-0.05, 0.05);
  Soup s;
  for (int t = 0; t < count; ++t) {
    const Vec3 c = testing_values::randomVector(u, rng);
    for (int k = 0; k < 3; ++k) s.x.push_back(c + testing_values::randomVector(e, rng));
    s.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return s;
}

bool boxTouchesTriangle(const Soup& s, int t, const Vec3& lo, const Vec3& hi) {
  Vec3 tlo = s.x[s.triangles[t][0]], thi = tlo;
  for (int32_t v : s.triangles[t]) tlo = tlo.cwiseMin(s.x[v]), thi = thi.cwiseMax(s.x[v]);
  return !((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any());
}

void checkAgainstBruteForce(const RefitBvh& bvh, const Soup& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  for (int q = 0; q < 50; ++q) {
    const Vec3 a = testing_values::randomVector(u, rng), b = testing_values::randomVector(u, rng);
    const Vec3 lo = a.cwiseMin(b) * 0.5 + Vec3::Constant(0.25), hi = lo + (a - b).cwiseAbs() * 0.2;
    std::set<int> visited;
    bvh.visitBox(lo, hi, [&](int32_t t) { visited.insert(t); });
    for (int t = 0; t < static_cast<int>(s.triangles.size()); ++t)
      ASSERT_EQ(visited.count(t) == 1, boxTouchesTriangle(s, t, lo, hi)) << "box query and triangle " << t;

    const double ox = u(rng), oy = u(rng), tx = u(rng), ty = u(rng);
    const Vec3 origin(ox, oy, -0.5);
    const Vec3 direction = (Vec3(tx, ty, 1.5) - origin).normalized();
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& tri : s.triangles) {
      TriangleRayHit h;
      if (rayHitsTriangle(origin, direction, nearest, s.x[tri[0]], s.x[tri[1]], s.x[tri[2]], &h)) nearest = h.distance;
    }
    double found = std::numeric_limits<double>::infinity();
    bvh.visitRay(origin, direction, found, [&](int32_t t, double limit) {
      const auto& tri = s.triangles[t];
      TriangleRayHit h;
      if (rayHitsTriangle(origin, direction, limit, s.x[tri[0]], s.x[tri[1]], s.x[tri[2]], &h)) return found = h.distance;
      return limit;
    });
    EXPECT_EQ(found, nearest);
  }
}

TEST(RefitBvh, QueriesMatchBruteForceAfterBuildAndAfterRefits) {
  std::mt19937 rng(7);
  Soup s = randomSoup(500, rng);
  RefitBvh bvh;
  bvh.rebuild(s.x, s.triangles);
  checkAgainstBruteForce(bvh, s, rng);
  std::uniform_real_distribution<double> e(-0.1, 0.1);
  for (int round = 0; round < 3; ++round) {
    for (Vec3& p : s.x) p += testing_values::randomVector(e, rng) + Vec3(0.3 * p.y(), 0.0, 0.0);  // shear and jitter
    bvh.refit(s.x, s.triangles);
    checkAgainstBruteForce(bvh, s, rng);
  }
}

TEST(RefitBvh, AMarginGrowsEachTrianglesBoxByItsOwnAmount) {
  // Two small triangles in the plane y = 0, two apart; only the second has a margin of 0.3.
  // (Visits are per leaf, so a box over the first is not a test of its own margin here.)
  const Soup s{{Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0, 0.1), Vec3(2, 0, 0), Vec3(2.1, 0, 0), Vec3(2, 0, 0.1)},
               {{0, 1, 2}, {3, 4, 5}}};
  RefitBvh grown, plain;
  grown.rebuild(s.x, s.triangles);
  plain.rebuild(s.x, s.triangles);
  const Array<double> margins{0.0, 0.3};
  grown.refit(s.x, s.triangles, &margins);
  auto visitedAbove = [&](const RefitBvh& bvh, double y) {
    std::set<int32_t> seen;
    bvh.visitBox(Vec3(2.0, y, 0.0), Vec3(2.05, y + 0.05, 0.05), [&](int32_t t) { seen.insert(t); });
    return seen.count(1) == 1;
  };
  EXPECT_TRUE(visitedAbove(grown, 0.25));   // within the second's margin
  EXPECT_FALSE(visitedAbove(plain, 0.25));  // which a plain refit does not have
  EXPECT_FALSE(visitedAbove(grown, 0.35));  // beyond it
  EXPECT_NEAR(grown.hi().y(), 0.3, 1e-15);  // the root holds the grown box
  EXPECT_NEAR(grown.lo().x(), 0.0, 1e-15);  // and the first triangle's, not grown
}

TEST(RefitBvh, AnEmptySurfaceVisitsNothing) {
  RefitBvh bvh;
  bvh.rebuild({}, {});
  int visits = 0;
  bvh.visitBox(Vec3::Zero(), Vec3::Ones(), [&](int32_t) { ++visits; });
  bvh.visitRay(Vec3::Zero(), Vec3::UnitX(), 10.0, [&](int32_t, double limit) { return ++visits, limit; });
  EXPECT_EQ(visits, 0);
  EXPECT_GT(bvh.lo().x(), bvh.hi().x());
}

}  // namespace
}  // namespace vp

// Face fraction field over a MAC grid, and the multi-collider (union) policy.
#include "collide/face_coverage.h"
#include "collide/face_coverage_detail.h"
#include "fluid/solids/face_fraction_field.h"
#include "fluid_face_test_util.h"
#include "random_values.h"

#include <gtest/gtest.h>

namespace vp {
namespace {

constexpr double kPi = 3.14159265358979323846;

PreparedCollider prepared(const ColliderShape& s) {
  PreparedCollider p;
  EXPECT_EQ(prepareCollider(s, &p), Status::Ok) << lastError();
  return p;
}

ColliderShape sphere(const Eigen::Vector3d& c, double r) {
  ColliderShape s;
  s.kind = ShapeKind::Sphere;
  s.radius = r;
  s.translation = c;
  return s;
}

TEST(FluidFaceField, LayoutAndValidation) {
  MacGridSpec g;
  g.nx = 3; g.ny = 4; g.nz = 5; g.h = 0.5;
  FaceFractionField f;
  ASSERT_EQ(initFaceFractionField(g, &f), Status::Ok);
  EXPECT_EQ(f.open[0].size(), 4u * 4 * 5);
  EXPECT_EQ(f.open[1].size(), 3u * 5 * 5);
  EXPECT_EQ(f.open[2].size(), 3u * 4 * 6);
  EXPECT_EQ(f.faceIndex(0, 1, 2, 3), 1u + 4 * (2 + 4 * 3));
  EXPECT_EQ(f.faceIndex(1, 1, 2, 3), 1u + 3 * (2 + 5 * 3));
  EXPECT_EQ(f.faceIndex(2, 1, 2, 3), 1u + 3 * (2 + 4 * 3));
  const AxisFace a = f.face(0, 1, 2, 3);
  EXPECT_TRUE(a.centre.isApprox(Eigen::Vector3d(0.5, 1.25, 1.75)));
  g.h = -1;
  EXPECT_EQ(initFaceFractionField(g, &f), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("h"), std::string::npos);
  g.h = 1; g.ny = 0;
  EXPECT_EQ(initFaceFractionField(g, &f), Status::InvalidArgument);
}

TEST(FluidFaceField, SphereSlabsMatchCrossSections) {
  const double r = 1.0;
  PreparedCollider s = prepared(sphere({0.013, -0.021, 0.007}, r));
  MacGridSpec g;
  g.origin = Eigen::Vector3d::Constant(-1.5);
  g.h = 0.1;
  g.nx = g.ny = g.nz = 30;
  FaceFractionField f;
  ASSERT_EQ(initFaceFractionField(g, &f), Status::Ok);
  const PreparedCollider* list[] = {&s};
  ASSERT_EQ(computeFaceFractions(list, 1, &f), Status::Ok);
  // The u-faces of one x plane tile it, so their covered areas sum to the disc pi (r^2 - dx^2)
  // (exact sphere path: round-off only).
  double worst = 0.0;
  for (int i = 0; i <= g.nx; ++i) {
    const double x = g.origin.x() + i * g.h, dx = x - s.translation.x();
    double covered = 0.0;
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j) covered += (1.0 - f.open[0][f.faceIndex(0, i, j, k)]) * g.h * g.h;
    const double expected = dx * dx < r * r ? kPi * (r * r - dx * dx) : 0.0;
    worst = std::max(worst, std::fabs(covered - expected));
  }
  EXPECT_LT(worst, 1e-11);
  // Same for y and z planes, summed over all planes: sum_i pi (r^2 - y_i^2) h ~ volume.
  for (int a = 1; a < 3; ++a) {
    const Eigen::Vector3i d = f.faceDims(a);
    double total = 0.0, expected = 0.0;
    for (int p = 0; p < d[a]; ++p) {
      const double y = g.origin[a] + p * g.h - s.translation[a];
      expected += y * y < r * r ? kPi * (r * r - y * y) : 0.0;
    }
    for (double o : f.open[a]) total += (1.0 - o) * g.h * g.h;
    EXPECT_NEAR(total, expected, 1e-10) << "axis " << a;
  }
}

TEST(FluidFaceField, ThinSlantedPlateBlocksEveryAxisLine) {
  // A plate one cell thick (thickness h), slanted. For a line along axis a, every point (y, z)
  // of the line's face footprint is inside the plate over an x-interval of length
  // h / |n_a| >= h, which always contains a face plane; integrating over the footprint gives
  // sum over the line's faces of covered >= 1: the union of the covered parts blocks the line.
  const double h = 0.1;
  ColliderShape plate;
  plate.kind = ShapeKind::Box;
  plate.halfExtents = Eigen::Vector3d(3.0, 0.5 * h, 3.0);
  plate.rotation = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(-0.35, Eigen::Vector3d::UnitX());
  plate.translation = Eigen::Vector3d(0.012, -0.007, 0.003);
  PreparedCollider p = prepared(plate);
  MacGridSpec g;
  g.origin = Eigen::Vector3d::Constant(-0.8);
  g.h = h;
  g.nx = g.ny = g.nz = 16;
  FaceFractionField f;
  ASSERT_EQ(initFaceFractionField(g, &f), Status::Ok);
  const PreparedCollider* list[] = {&p};
  ASSERT_EQ(computeFaceFractions(list, 1, &f), Status::Ok);
  const Eigen::Vector3d n = p.rotation.col(1);
  int lines = 0, someFaceFull = 0;
  for (int a = 0; a < 3; ++a) {
    const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    const Eigen::Vector3i d = f.faceDims(a);
    for (int q = 0; q < d[a2]; ++q)
      for (int pp = 0; pp < d[a1]; ++pp) {
        // Does the plate's mid-plane cross this line inside the grid (with a cell of margin)?
        Eigen::Vector3d c = g.origin + g.h * Eigen::Vector3d::Constant(0.5);
        c[a1] = g.origin[a1] + (pp + 0.5) * g.h;
        c[a2] = g.origin[a2] + (q + 0.5) * g.h;
        c[a] = 0.0;
        const double s = -n.dot(c - p.translation) / n[a];
        if (s < g.origin[a] + 2 * g.h || s > g.origin[a] + (d[a] - 3) * g.h) continue;
        double sum = 0.0, maxCovered = 0.0;
        for (int i = 0; i < d[a]; ++i) {
          int idx[3];
          idx[a] = i; idx[a1] = pp; idx[a2] = q;
          const double cov = 1.0 - f.open[a][f.faceIndex(a, idx[0], idx[1], idx[2])];
          sum += cov;
          maxCovered = std::max(maxCovered, cov);
        }
        ++lines;
        someFaceFull += maxCovered == 1.0;
        EXPECT_GE(sum, 1.0 - 1e-12) << "axis " << a << " line " << pp << "," << q;
        EXPECT_GE(maxCovered, 0.5 - 1e-12) << "axis " << a << " line " << pp << "," << q;
      }
  }
  EXPECT_GT(lines, 300);
  std::printf("slanted plate: %d axis lines checked, %d have a fully closed face\n", lines,
              someFaceFull);
}

TEST(FluidFaceField, IncrementalUpdateEqualsFullRecompute) {
  PreparedCollider s = prepared(sphere({0.1, 0.2, -0.1}, 0.45));
  ColliderShape cap;
  cap.kind = ShapeKind::Capsule;
  cap.radius = 0.2;
  cap.halfHeight = 0.3;
  cap.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  cap.translation = Eigen::Vector3d(-0.3, 0.0, 0.2);  // overlaps the sphere
  cap.angularVelocity = Eigen::Vector3d(0.5, -1.0, 2.0);
  cap.linearVelocity = Eigen::Vector3d(1.0, 0.0, -0.5);
  PreparedCollider c = prepared(cap);
  MacGridSpec g;
  g.origin = Eigen::Vector3d::Constant(-1.0);
  g.h = 0.1;
  g.nx = 20; g.ny = 18; g.nz = 22;
  FaceFractionField inc, full;
  ASSERT_EQ(initFaceFractionField(g, &inc), Status::Ok);
  ASSERT_EQ(initFaceFractionField(g, &full), Status::Ok);
  const PreparedCollider* list[] = {&s, &c};
  ASSERT_EQ(computeFaceFractions(list, 2, &inc), Status::Ok);
  const Aabb before = c.bounds;
  ASSERT_EQ(setColliderPose(&c, Eigen::Quaterniond(Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitY())),
                            Eigen::Vector3d(0.35, -0.25, 0.05)), Status::Ok);
  ASSERT_EQ(updateFaceFractions(list, 2, before, c.bounds, &inc), Status::Ok);
  ASSERT_EQ(computeFaceFractions(list, 2, &full), Status::Ok);
  int changed = 0;
  for (int a = 0; a < 3; ++a) {
    for (size_t i = 0; i < full.open[a].size(); ++i) {
      ASSERT_EQ(inc.open[a][i], full.open[a][i]) << "axis " << a << " face " << i;
      ASSERT_EQ(inc.solidVelocity[a][i], full.solidVelocity[a][i]) << "axis " << a << " face " << i;
      changed += full.open[a][i] < 1.0;
    }
  }
  EXPECT_GT(changed, 100);
  // Without the update the field would be stale: the check above can fail.
  FaceFractionField stale;
  ASSERT_EQ(initFaceFractionField(g, &stale), Status::Ok);
  ASSERT_EQ(setColliderPose(&c, cap.rotation, cap.translation), Status::Ok);
  ASSERT_EQ(computeFaceFractions(list, 2, &stale), Status::Ok);
  EXPECT_NE(stale.open[0], full.open[0]);
}

TEST(FluidFaceField, SolidVelocityIsNormalComponentAtCoveredCentroid) {
  ColliderShape b;
  b.kind = ShapeKind::Box;
  b.halfExtents = Eigen::Vector3d(2, 2, 2);
  b.translation = Eigen::Vector3d(2.0, 0, 0);  // covers x >= 0
  b.linearVelocity = Eigen::Vector3d(0.3, -0.2, 0.1);
  b.angularVelocity = Eigen::Vector3d(0, 0, 1.0);  // v_x = -(y - 0)
  PreparedCollider p = prepared(b);
  MacGridSpec g;
  g.origin = Eigen::Vector3d(-1.05, -1, -1);
  g.h = 0.1;
  g.nx = g.ny = g.nz = 20;
  FaceFractionField f;
  ASSERT_EQ(initFaceFractionField(g, &f), Status::Ok);
  const PreparedCollider* list[] = {&p};
  ASSERT_EQ(computeFaceFractions(list, 1, &f), Status::Ok);
  // v-face (axis 1) at j = 10 (y = 0) straddling x = 0 (cell i = 10 spans [-0.05, 0.05]):
  // half covered, covered centroid x = 0.025; v_y = -0.2 + wz * (x - 2).
  const size_t vf = f.faceIndex(1, 10, 10, 10);
  EXPECT_NEAR(f.open[1][vf], 0.5, 1e-12);
  EXPECT_NEAR(f.solidVelocity[1][vf], -0.2 + (0.025 - 2.0), 1e-12);
  // u-face fully covered at x = 0.45, y centre 0.05: v_x = 0.3 - 1 * 0.05.
  const size_t uf = f.faceIndex(0, 15, 10, 10);
  EXPECT_EQ(f.open[0][uf], 0.0);
  EXPECT_NEAR(f.solidVelocity[0][uf], 0.3 - 0.05, 1e-12);
  // Open faces carry no solid velocity.
  EXPECT_EQ(f.solidVelocity[0][f.faceIndex(0, 2, 10, 10)], 0.0);
}

TEST(FluidFaceUnion, OverlappingCollidersAgainstSupersampling) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-0.35, 0.35);
  double maxErr = 0.0;
  int checked = 0;
  for (int t = 0; t < 6; ++t) {
    ColliderShape a = sphere({u(rng), u(rng), u(rng)}, 0.35);
    ColliderShape b;
    b.kind = t % 2 ? ShapeKind::Cylinder : ShapeKind::Box;
    b.radius = 0.25;
    b.halfHeight = 0.4;
    b.halfExtents = Eigen::Vector3d(0.3, 0.2, 0.4);
    b.rotation = testutil::randomRotation(rng);
    b.translation = testing_values::randomVector(u, rng);
    PreparedCollider pa = prepared(a), pb = prepared(b);
    const PreparedCollider* list[] = {&pa, &pb};
    const AxisFace f = testutil::unitFace(t % 3);
    const double got = coveredFractionUnion(list, 2, f);
    const double ref = testutil::supersample(f, 800, [&](const Eigen::Vector3d& x) {
      return testutil::insideWorld(a, x) || testutil::insideWorld(b, x);
    });
    const double sum = coveredFraction(pa, f) + coveredFraction(pb, f);
    maxErr = std::max(maxErr, std::fabs(got - ref));
    checked += sum - ref > 0.01;  // the solids really overlap on this face
    EXPECT_NEAR(got, ref, 1e-3) << "trial " << t;
  }
  EXPECT_GE(checked, 2);
  std::printf("union vs supersampling(800^2): max error %.3g\n", maxErr);
}

TEST(FluidFaceUnion, DisjointCollidersUseExactPaths) {
  PreparedCollider a = prepared(sphere({-0.3, 0, 0}, 0.15)), b = prepared(sphere({0.3, 0, 0}, 0.1));
  const PreparedCollider* list[] = {&a, &b};
  EXPECT_NEAR(coveredFractionUnion(list, 2, testutil::unitFace(2)), kPi * (0.0225 + 0.01), 1e-12);
}

ColliderShape box(const Eigen::Vector3d& c, const Eigen::Vector3d& halfExtents) {
  ColliderShape s;
  s.kind = ShapeKind::Box;
  s.halfExtents = halfExtents;
  s.translation = c;
  return s;
}

// The disc-in-polygon area against the closed form for rectangles, in both orientations, for
// discs inside, around, across corners and outside.
TEST(FluidFaceUnion, DiscPolygonAreaMatchesTheRectangleFormula) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), radius(0.05, 1.5);
  for (int t = 0; t < 200; ++t) {
    const double x0 = u(rng), y0 = u(rng), x1 = x0 + 0.1 + std::fabs(u(rng)), y1 = y0 + 0.1 + std::fabs(u(rng));
    const double cx = u(rng), cy = u(rng), r = radius(rng);
    const double ccw[2][4] = {{x0, x1, x1, x0}, {y0, y0, y1, y1}};
    const double cw[2][4] = {{x0, x0, x1, x1}, {y0, y1, y1, y0}};
    const double want = detail::discRectangleArea(cx, cy, r, x0, y0, x1, y1);
    EXPECT_NEAR(detail::discPolygonArea(cx, cy, r, ccw[0], ccw[1], 4), want, 1e-13) << "trial " << t;
    EXPECT_NEAR(detail::discPolygonArea(cx, cy, r, cw[0], cw[1], 4), want, 1e-13) << "trial " << t;
  }
}

// Unions with a known area: two overlapping boxes (the overlap counted once), and a box
// covering half the face beside a sphere centred on the face's midline (the half disc
// outside the box adds pi r^2 / 2).
TEST(FluidFaceUnion, PolyhedraAndOneSphereAreExact) {
  const AxisFace f = testutil::unitFace(1);  // y = 0, u = z, v = x, both in [-0.5, 0.5]
  PreparedCollider a = prepared(box({-0.3, 0, 0.1}, {0.4, 1, 0.3})), b = prepared(box({0.1, 0, -0.2}, {0.25, 1, 0.2}));
  const PreparedCollider* boxes[] = {&a, &b};
  // a covers x in [-0.5, 0.1], z in [-0.2, 0.4]; b covers x in [-0.15, 0.35], z in [-0.4, 0];
  // they share x in [-0.15, 0.1], z in [-0.2, 0].
  EXPECT_NEAR(coveredFractionUnion(boxes, 2, f), 0.6 * 0.6 + 0.5 * 0.4 - 0.25 * 0.2, 1e-14);

  const double r = 0.3;
  PreparedCollider half = prepared(box({0.5, 0, 0}, {0.5, 1, 1})), ball = prepared(sphere({0, 0, 0}, r));
  const PreparedCollider* mixed[] = {&half, &ball};
  EXPECT_NEAR(coveredFractionUnion(mixed, 2, f), 0.5 + 0.5 * kPi * r * r, 1e-14);

  // A half-space x <= -0.4 besides: it adds the strip x < -0.4 less its part inside the disc.
  ColliderShape wall;
  wall.kind = ShapeKind::Plane;
  wall.planeNormal = Eigen::Vector3d(1, 0, 0);
  wall.planeOffset = -0.4;
  PreparedCollider g = prepared(wall);
  const PreparedCollider* three[] = {&half, &ball, &g};
  const double strip = 0.1 - detail::discRectangleArea(0, 0, r, -0.5, -0.5, -0.4, 0.5);  // x < -0.4, |z| <= 0.5
  EXPECT_NEAR(coveredFractionUnion(three, 3, f), 0.5 + 0.5 * kPi * r * r + strip, 1e-14);
}

// Rotated boxes, half-spaces and a sphere in random overlapping poses against fine
// supersampling; the midpoint rule's error on these boundaries is below the tolerance.
TEST(FluidFaceUnion, RandomPolyhedraAndASphereAgainstSupersampling) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  int overlapping = 0;
  for (int t = 0; t < 8; ++t) {
    std::vector<ColliderShape> shapes;
    const Eigen::Vector3d centre = testing_values::randomVector(u, rng);
    shapes.push_back(sphere(centre, 0.3 + 0.1 * std::fabs(u(rng))));
    ColliderShape b = box({u(rng), u(rng), u(rng)}, {0.3, 0.15, 0.4});
    b.rotation = testutil::randomRotation(rng);
    shapes.push_back(b);
    if (t % 2) {
      ColliderShape p;
      p.kind = ShapeKind::Plane;
      p.rotation = testutil::randomRotation(rng);
      p.planeOffset = -0.2;
      shapes.push_back(p);
    }
    std::vector<PreparedCollider> solids;
    for (const ColliderShape& s : shapes) solids.push_back(prepared(s));
    std::vector<const PreparedCollider*> list;
    double sum = 0.0;
    const AxisFace f = testutil::unitFace(t % 3);
    for (const PreparedCollider& s : solids) {
      list.push_back(&s);
      sum += coveredFraction(s, f);
    }
    const double ref = testutil::supersample(f, 2000, [&](const Eigen::Vector3d& x) {
      for (const ColliderShape& s : shapes)
        if (testutil::insideWorld(s, x)) return true;
      return false;
    });
    overlapping += sum - ref > 0.01;
    EXPECT_NEAR(coveredFractionUnion(list.data(), static_cast<int>(list.size()), f), ref, 1e-4) << "trial " << t;
  }
  EXPECT_GE(overlapping, 3);
}

}  // namespace
}  // namespace vp

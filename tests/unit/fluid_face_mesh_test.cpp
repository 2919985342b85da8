// Triangle-mesh face coverage (exact Green's-theorem path). A mesh of a convex polyhedron must
// agree with the exact hull/box paths to round-off; an icosphere must be sandwiched between
// its inner and outer spheres (exact sphere path) on every face; a 20K-triangle mesh must be
// fast enough to fill a grid.
#include "collide/face_coverage.h"
#include "fluid/solids/face_fraction_field.h"
#include "fluid_face_test_util.h"
#include "random_values.h"

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <vector>

namespace vp {
namespace {

void cubeMesh(const Eigen::Vector3d& he, const Eigen::Vector3d& offset, ColliderShape* s) {
  const int base = static_cast<int>(s->meshVertices.size());
  for (int c = 0; c < 8; ++c)
    s->meshVertices.push_back(offset + Eigen::Vector3d(c & 1 ? he.x() : -he.x(),
                                                       c & 2 ? he.y() : -he.y(),
                                                       c & 4 ? he.z() : -he.z()));
  // Outward quads (corner bits: x=1, y=2, z=4).
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    s->meshTriangles.emplace_back(base + q[0], base + q[1], base + q[2]);
    s->meshTriangles.emplace_back(base + q[0], base + q[2], base + q[3]);
  }
}

ColliderShape icosphere(int subdivisions, double r) {
  ColliderShape s;
  s.kind = ShapeKind::TriangleMesh;
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  Array<Eigen::Vector3d> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0},
                                    {0, -1, p}, {0, 1, p}, {0, -1, -p}, {0, 1, -p},
                                    {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  Array<Eigen::Vector3i> t = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& x : v) x.normalize();
  for (int s_ = 0; s_ < subdivisions; ++s_) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    Array<Eigen::Vector3i> nt;
    for (const auto& tri : t) {
      const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      nt.emplace_back(tri[0], a, c);
      nt.emplace_back(tri[1], b, a);
      nt.emplace_back(tri[2], c, b);
      nt.emplace_back(a, b, c);
    }
    t = nt;
  }
  for (auto& x : v) x *= r;
  s.meshVertices = v;
  s.meshTriangles = t;
  return s;
}

// Reference for the covered part's centroid, written independently of the Green's-theorem
// path: the face square clipped (Sutherland-Hodgman) by the box's six half-spaces restricted
// to the face's plane, then the polygon's area centroid. Returns the covered area.
double clippedBoxCentroid(const Eigen::Vector3d& he, const Eigen::Quaterniond& q, const Eigen::Vector3d& t,
                          const AxisFace& f, Eigen::Vector2d* centroid) {
  const int a1 = (f.axis + 1) % 3, a2 = (f.axis + 2) % 3;
  std::vector<Eigen::Vector2d> poly;
  for (int c : {0, 1, 3, 2})
    poly.emplace_back(f.centre[a1] + (c & 1 ? 0.5 : -0.5) * f.h, f.centre[a2] + (c & 2 ? 0.5 : -0.5) * f.h);
  const Eigen::Matrix3d R = q.toRotationMatrix();
  for (int side = 0; side < 6; ++side) {
    const Eigen::Vector3d n = (side < 3 ? 1.0 : -1.0) * R.col(side % 3);
    const double d = n.dot(t) + he[side % 3];  // n.x <= d inside
    auto value = [&](const Eigen::Vector2d& p) {
      return n[a1] * p.x() + n[a2] * p.y() + n[f.axis] * f.centre[f.axis] - d;
    };
    std::vector<Eigen::Vector2d> out;
    for (size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d& p = poly[i];
      const Eigen::Vector2d& r = poly[(i + 1) % poly.size()];
      const double vp = value(p), vr = value(r);
      if (vp <= 0.0) out.push_back(p);
      if ((vp < 0.0) != (vr < 0.0) && vp != vr) out.push_back(p + (r - p) * (vp / (vp - vr)));
    }
    poly = out;
    if (poly.empty()) return 0.0;
  }
  double area = 0.0;
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d& p = poly[i];
    const Eigen::Vector2d& r = poly[(i + 1) % poly.size()];
    const double cross = p.x() * r.y() - r.x() * p.y();
    area += 0.5 * cross;
    m += (p + r) * cross / 6.0;
  }
  *centroid = m / area;
  return area;
}

// The covered part's centroid is exact: the same fraction as coveredFraction gives, and the
// clipped polygon's centroid to round-off (the rule is exact for straight edges).
void expectCentroidOfClippedBox(const PreparedCollider& pm, const Eigen::Vector3d& he, const Eigen::Quaterniond& q,
                                const Eigen::Vector3d& t, const AxisFace& f) {
  Eigen::Vector3d centroid;
  const double a = coveredFractionAndCentroid(pm, f, &centroid);
  EXPECT_EQ(a, coveredFraction(pm, f));
  Eigen::Vector2d expected;
  const double area = clippedBoxCentroid(he, q, t, f, &expected);
  EXPECT_NEAR(a, area / (f.h * f.h), 1e-12);
  if (area < 1e-6) {
    EXPECT_EQ(centroid, f.centre);
    return;
  }
  EXPECT_NEAR(centroid[(f.axis + 1) % 3], expected.x(), 1e-10);
  EXPECT_NEAR(centroid[(f.axis + 2) % 3], expected.y(), 1e-10);
  EXPECT_EQ(centroid[f.axis], f.centre[f.axis]);
}

// A box as triangles covers every face as the box does, and its covered parts' centroids are
// exact.
TEST(FluidFaceMesh, CubeAsTrianglesEqualsBox) {
  ColliderShape m;
  m.kind = ShapeKind::TriangleMesh;
  const Eigen::Vector3d he(0.4, 0.3, 0.6);
  cubeMesh(he, Eigen::Vector3d::Zero(), &m);
  PreparedCollider pm;
  ASSERT_EQ(prepareCollider(m, &pm), Status::Ok) << lastError();
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  int partial = 0;
  for (int t = 0; t < 40; ++t) {
    const Eigen::Quaterniond q = testutil::randomRotation(rng);
    const Eigen::Vector3d tr = testing_values::randomVector(u, rng);
    ASSERT_EQ(setColliderPose(&pm, q, tr), Status::Ok);
    ColliderShape b;
    b.kind = ShapeKind::Box;
    b.halfExtents = he;
    b.rotation = q;
    b.translation = tr;
    const AxisFace f = testutil::unitFace(t % 3, Eigen::Vector3d::Zero(), 0.8);
    const double fb = coveredFraction(b, f);
    EXPECT_NEAR(coveredFraction(pm, f), fb, 1e-12) << "trial " << t;
    partial += (fb > 0.02 && fb < 0.98) ? 1 : 0;
    expectCentroidOfClippedBox(pm, he, q, tr, f);
  }
  EXPECT_GE(partial, 10);
}

// A mesh split along seams (every triangle with vertices of its own, as importers write texture
// seams) is closed once welded, by the same rule as a deformable's surfaceFile, and covers
// faces exactly as the welded mesh does.
TEST(FluidFaceMesh, MeshSplitAlongSeamsIsClosedAndCoversAsWelded) {
  ColliderShape welded;
  welded.kind = ShapeKind::TriangleMesh;
  cubeMesh(Eigen::Vector3d(0.3, 0.2, 0.25), Eigen::Vector3d(0.1, 0, 0), &welded);
  ColliderShape split = welded;
  split.meshVertices.clear();
  for (Eigen::Vector3i& t : split.meshTriangles)
    for (int c = 0; c < 3; ++c) {
      split.meshVertices.push_back(welded.meshVertices[static_cast<size_t>(t[c])]);
      t[c] = static_cast<int>(split.meshVertices.size()) - 1;
    }
  PreparedCollider pw, ps;
  ASSERT_EQ(prepareCollider(welded, &pw), Status::Ok) << lastError();
  ASSERT_EQ(prepareCollider(split, &ps), Status::Ok) << lastError();
  for (int axis = 0; axis < 3; ++axis) {
    const AxisFace f = testutil::unitFace(axis, Eigen::Vector3d(0.05, -0.02, 0.03), 0.8);
    EXPECT_EQ(coveredFraction(ps, f), coveredFraction(pw, f)) << "axis " << axis;
  }
  split.meshTriangles.pop_back();  // a hole: named by the shared rule
  EXPECT_EQ(prepareCollider(split, &ps), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("triangleMesh: is not closed: edge ("), std::string::npos) << lastError();
}

TEST(FluidFaceMesh, InwardOrientedMeshIsFlipped) {
  ColliderShape m;
  m.kind = ShapeKind::TriangleMesh;
  cubeMesh(Eigen::Vector3d(0.3, 0.3, 0.3), Eigen::Vector3d(0.2, 0, 0), &m);
  for (auto& t : m.meshTriangles) std::swap(t[1], t[2]);
  EXPECT_NEAR(coveredFraction(m, testutil::unitFace(2)), 0.36, 1e-12);
}

TEST(FluidFaceMesh, TwoDisjointCubesInOneMeshAddUp) {
  ColliderShape m;
  m.kind = ShapeKind::TriangleMesh;
  cubeMesh(Eigen::Vector3d(0.2, 0.1, 0.5), Eigen::Vector3d(-0.25, 0.1, 0), &m);
  cubeMesh(Eigen::Vector3d(0.1, 0.3, 0.5), Eigen::Vector3d(0.3, -0.1, 0), &m);
  // Axis-aligned: 0.4 * 0.2 + 0.2 * 0.6 on a z-face.
  EXPECT_NEAR(coveredFraction(m, testutil::unitFace(2)), 0.08 + 0.12, 1e-12);
}

TEST(FluidFaceMesh, IcosphereEqualsHullOfItsVertices) {
  const ColliderShape m = icosphere(1, 0.45);  // 80 triangles, 42 vertices (hull <= 256 planes)
  ColliderShape h;
  h.kind = ShapeKind::ConvexHull;
  h.hullPoints = m.meshVertices;
  PreparedCollider pm, ph;
  ASSERT_EQ(prepareCollider(m, &pm), Status::Ok) << lastError();
  ASSERT_EQ(prepareCollider(h, &ph), Status::Ok) << lastError();
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int t = 0; t < 40; ++t) {
    const Eigen::Quaterniond q = testutil::randomRotation(rng);
    const Eigen::Vector3d tr = testing_values::randomVector(u, rng);
    ASSERT_EQ(setColliderPose(&pm, q, tr), Status::Ok);
    ASSERT_EQ(setColliderPose(&ph, q, tr), Status::Ok);
    const AxisFace f = testutil::unitFace(t % 3, Eigen::Vector3d::Zero(), 0.6);
    EXPECT_NEAR(coveredFraction(pm, f), coveredFraction(ph, f), 1e-9) << "trial " << t;
  }
}

TEST(FluidFaceMesh, FineIcosphereSandwichedBetweenSpheresOnAGrid) {
  const ColliderShape m = icosphere(5, 1.0);  // 20480 triangles
  ASSERT_EQ(m.meshTriangles.size(), 20480u);
  PreparedCollider pm;
  auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(prepareCollider(m, &pm), Status::Ok) << lastError();
  double rin = 1.0;  // inscribed radius: smallest distance from the centre to a face plane
  for (const auto& t : pm.triangles) {
    const Eigen::Vector3d& a = pm.worldVertices[t[0]];
    const Eigen::Vector3d n = (pm.worldVertices[t[1]] - a).cross(pm.worldVertices[t[2]] - a).normalized();
    rin = std::min(rin, n.dot(a));
  }
  ColliderShape outer, inner;
  outer.kind = inner.kind = ShapeKind::Sphere;
  outer.radius = 1.0;
  inner.radius = rin;
  PreparedCollider po, pi;
  ASSERT_EQ(prepareCollider(outer, &po), Status::Ok);
  ASSERT_EQ(prepareCollider(inner, &pi), Status::Ok);
  MacGridSpec g;
  g.origin = Eigen::Vector3d::Constant(-1.2);
  g.h = 0.1;
  g.nx = g.ny = g.nz = 24;
  FaceFractionField field;
  ASSERT_EQ(initFaceFractionField(g, &field), Status::Ok);
  const PreparedCollider* list[] = {&pm};
  ASSERT_EQ(computeFaceFractions(list, 1, &field), Status::Ok);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  int partial = 0;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = field.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) {
          const AxisFace f = field.face(a, i, j, k);
          const double covered = 1.0 - field.open[a][field.faceIndex(a, i, j, k)];
          ASSERT_LE(covered, coveredFraction(po, f) + 1e-9) << a << " " << i << " " << j << " " << k;
          ASSERT_GE(covered, coveredFraction(pi, f) - 1e-9) << a << " " << i << " " << j << " " << k;
          partial += covered > 0.0 && covered < 1.0;
        }
  }
  EXPECT_GT(partial, 1000);
  std::printf("20480-triangle icosphere: inner radius %.6f, prepare + 3x25x24x24 faces in %.0f ms\n", rin, ms);
}

TEST(FluidFaceMesh, RejectsOpenMesh) {
  ColliderShape m;
  m.kind = ShapeKind::TriangleMesh;
  cubeMesh(Eigen::Vector3d(0.3, 0.3, 0.3), Eigen::Vector3d::Zero(), &m);
  m.meshTriangles.pop_back();
  PreparedCollider p;
  EXPECT_EQ(prepareCollider(m, &p), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("not closed"), std::string::npos) << lastError();
  m.meshTriangles.back()[0] = 99;
  EXPECT_EQ(prepareCollider(m, &p), Status::InvalidArgument);
}

}  // namespace
}  // namespace vp

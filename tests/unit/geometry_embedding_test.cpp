// Embedding of render points in a tet mesh and their evaluation under deformation.
#include "geometry/embedding.h"

#include "geometry/voxel_tetrahedralizer.h"

#include "geometry_test_shapes.h"
#include "random_values.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <random>

namespace vp {
namespace {

// Barycentric coordinates are computed as l0 = 1 - (l1 + l2 + l3): the sum is 1 up to a
// few ulps. Reconstructing p = sum l_i x_i loses about cond(tet) * eps * |x|; voxel tets
// have condition number ~ 4 and the meshes here have |x| <= 3, so 1e-12 leaves >100x margin
// while any wrong tet or wrong coordinate shows up at the 1e-3 level.
constexpr double kRoundOff = 1e-12;

struct SphereMesh {
  SurfaceMesh surface;
  TetMesh mesh;
  VoxelGrid grid;
};

SphereMesh voxelSphere(int resolution) {
  SphereMesh s;
  s.surface = test::icosphere(3, 1.0);
  EXPECT_EQ(tetrahedralizeVoxels(s.surface, resolution, &s.mesh, &s.grid), Status::Ok) << lastError();
  return s;
}

Array<Eigen::Vector3d> randomPointsInBall(size_t n, double radius, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-radius, radius);
  Array<Eigen::Vector3d> points;
  while (points.size() < n) {
    Eigen::Vector3d p = testing_values::randomVector(u, rng);
    if (p.norm() < radius) points.push_back(p);
  }
  return points;
}

Eigen::Vector3d reconstruct(const TetMesh& mesh, const EmbeddedPoint& e) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) p += e.barycentric[k] * mesh.vertices[mesh.tets[e.tet][k]];
  return p;
}

double minCoordinate(const EmbeddedPoint& e) {
  return std::min({e.barycentric[0], e.barycentric[1], e.barycentric[2], e.barycentric[3]});
}

TEST(GeometryEmbedding, InsidePointsHaveNonNegativeCoordinates) {
  const SphereMesh s = voxelSphere(10);
  // Inside the analytic sphere of radius 0.99 < inscribed radius of the icosphere, hence
  // inside the tets (which cover the icosphere), plus the surface vertices themselves.
  Array<Eigen::Vector3d> points = randomPointsInBall(2000, 0.99 * std::cos(0.2), 1);
  points.insert(points.end(), s.surface.vertices.begin(), s.surface.vertices.end());
  // Lattice vertices of the tet mesh: on shared faces/edges of many tets.
  for (size_t v = 0; v < s.mesh.vertices.size(); v += 7) points.push_back(s.mesh.vertices[v]);

  Array<EmbeddedPoint> embedding;
  EmbeddingReport report;
  ASSERT_EQ(embedPoints(s.mesh, points, &embedding, &report), Status::Ok) << lastError();
  ASSERT_EQ(embedding.size(), points.size());
  EXPECT_EQ(report.outsidePoints, 0);  // the voxel hull covers the surface
  for (size_t i = 0; i < points.size(); ++i) {
    const auto& e = embedding[i];
    ASSERT_GE(e.tet, 0);
    const double sum = e.barycentric[0] + e.barycentric[1] + e.barycentric[2] + e.barycentric[3];
    EXPECT_NEAR(sum, 1.0, kRoundOff) << i;
    EXPECT_GE(minCoordinate(e), -kRoundOff) << i;
    EXPECT_LT((reconstruct(s.mesh, e) - points[i]).norm(), kRoundOff) << i;
  }
}

TEST(GeometryEmbedding, OutsidePointsGetTheNearestTet) {
  const SphereMesh s = voxelSphere(8);
  Array<Eigen::Vector3d> points;
  std::mt19937 rng(2);
  std::normal_distribution<double> g;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d dir = testing_values::randomVector(g, rng).normalized();
    points.push_back(dir * (1.6 + 0.01 * i));  // outside the hull (at most 1 + sqrt(3) h)
  }
  points.emplace_back(40.0, -3.0, 2.0);  // far outside the grid
  Array<EmbeddedPoint> embedding;
  EmbeddingReport report;
  ASSERT_EQ(embedPoints(s.mesh, points, &embedding, &report), Status::Ok) << lastError();
  EXPECT_EQ(report.outsidePoints, static_cast<int64_t>(points.size()));
  double maxDistance = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    // Brute force over all tets must not find a closer one.
    double nearest = INFINITY;
    for (size_t t = 0; t < s.mesh.tets.size(); ++t)
      nearest = std::min(nearest, pointTetDistance(s.mesh, static_cast<int32_t>(t), points[i]));
    EXPECT_EQ(pointTetDistance(s.mesh, embedding[i].tet, points[i]), nearest) << i;
    maxDistance = std::max(maxDistance, nearest);
    // Extrapolated coordinates still reproduce the point and sum to 1.
    const auto& l = embedding[i].barycentric;
    EXPECT_NEAR(l[0] + l[1] + l[2] + l[3], 1.0, kRoundOff * points[i].norm()) << i;
    EXPECT_LT((reconstruct(s.mesh, embedding[i]) - points[i]).norm(), kRoundOff * points[i].norm()) << i;
    EXPECT_LT(minCoordinate(embedding[i]), 0.0) << i;
  }
  EXPECT_EQ(report.maxOutsideDistance, maxDistance);
}

TEST(GeometryEmbedding, PointTetDistance) {
  TetMesh tet;
  tet.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tet.tets = {{{0, 1, 2, 3}}};
  EXPECT_EQ(pointTetDistance(tet, 0, {0.1, 0.1, 0.1}), 0.0);
  EXPECT_DOUBLE_EQ(pointTetDistance(tet, 0, {0.2, 0.2, -0.5}), 0.5);           // below face z = 0
  EXPECT_DOUBLE_EQ(pointTetDistance(tet, 0, {-1, -1, -1}), std::sqrt(3.0));    // nearest is vertex 0
  EXPECT_DOUBLE_EQ(pointTetDistance(tet, 0, {1, 1, 1}), 2.0 / std::sqrt(3.0));  // off the slanted face
  EXPECT_DOUBLE_EQ(pointTetDistance(tet, 0, {0.5, -1, -1}), std::sqrt(2.0));   // nearest is edge 0-1
}

TEST(GeometryEmbedding, RenderMeshFollowsRigidMotion) {
  const SphereMesh s = voxelSphere(9);
  // The render mesh: the icosphere, with every third vertex pushed out to 1.5 x radius so
  // that some points lie outside the voxel hull and use extrapolated coordinates.
  SurfaceMesh render = s.surface;
  for (size_t v = 0; v < render.vertices.size(); v += 3) render.vertices[v] *= 1.5;
  Array<EmbeddedPoint> embedding;
  EmbeddingReport report;
  ASSERT_EQ(embedPoints(s.mesh, render.vertices, &embedding, &report), Status::Ok) << lastError();
  EXPECT_GT(report.outsidePoints, 0);

  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.1, Eigen::Vector3d(-0.3, 0.8, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(1.5, -2.0, 0.7);
  Array<Eigen::Vector3d> deformed;
  for (const auto& x : s.mesh.vertices) deformed.push_back(R * x + t);

  Array<Eigen::Vector3d> positions;
  ASSERT_EQ(evaluateEmbedded(s.mesh.tets, deformed, embedding, &positions), Status::Ok) << lastError();
  ASSERT_EQ(positions.size(), render.vertices.size());
  // Extrapolated points (|l| up to ~10) amplify round-off accordingly.
  for (size_t i = 0; i < positions.size(); ++i)
    EXPECT_LT((positions[i] - (R * render.vertices[i] + t)).norm(), 10 * kRoundOff) << i;

  Array<Eigen::Vector3d> restNormals, movedNormals;
  ASSERT_EQ(computeVertexNormals(render.vertices, render.triangles, &restNormals), Status::Ok);
  ASSERT_EQ(computeVertexNormals(positions, render.triangles, &movedNormals), Status::Ok);
  for (size_t i = 0; i < positions.size(); ++i) {
    EXPECT_NEAR(restNormals[i].norm(), 1.0, kRoundOff);
    EXPECT_LT((movedNormals[i] - R * restNormals[i]).norm(), 1e-9) << i;  // normalization of ~1e-12 errors
  }
}

TEST(GeometryEmbedding, VertexNormalsAreAreaWeighted) {
  // Two triangles at vertex 0: one in the xy plane (area 2), one in the xz plane (area 0.5).
  const Array<Eigen::Vector3d> x = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, -1}};
  const Array<std::array<int32_t, 3>> tris = {{{0, 1, 2}}, {{0, 1, 3}}};
  Array<Eigen::Vector3d> normals;
  ASSERT_EQ(computeVertexNormals(x, tris, &normals), Status::Ok);
  // Face normals: +z with area 2 and (2,0,0)x(0,0,-1) = (0,2,0)/2 -> +y with area 1.
  EXPECT_LT((normals[0] - Eigen::Vector3d(0, 1, 2).normalized()).norm(), 1e-15);
  EXPECT_LT((normals[2] - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
  EXPECT_LT((normals[3] - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
}

TEST(GeometryEmbedding, Errors) {
  const SphereMesh s = voxelSphere(4);
  Array<EmbeddedPoint> embedding(3);
  Array<Eigen::Vector3d> points = {{0, 0, 0}, {0.1, NAN, 0}};
  EXPECT_EQ(embedPoints(s.mesh, points, &embedding), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("point 1"), std::string::npos) << lastError();
  EXPECT_EQ(embedding.size(), 3u);
  EXPECT_EQ(embedPoints(TetMesh{}, {{0, 0, 0}}, &embedding), Status::InvalidArgument);
  TetMesh flat = s.mesh;
  flat.vertices[flat.tets[5][3]] = flat.vertices[flat.tets[5][0]];
  EXPECT_EQ(embedPoints(flat, {{0, 0, 0}}, &embedding), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("degenerate"), std::string::npos) << lastError();

  ASSERT_EQ(embedPoints(s.mesh, {{0, 0, 0}, {0.2, 0.1, 0}}, &embedding), Status::Ok);
  Array<Eigen::Vector3d> positions(1);
  Array<Eigen::Vector3d> tooFew(s.mesh.vertices.begin(), s.mesh.vertices.begin() + 2);
  EXPECT_EQ(evaluateEmbedded(s.mesh.tets, tooFew, embedding, &positions), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("point 0"), std::string::npos) << lastError();
  EXPECT_EQ(positions.size(), 1u);
  embedding[1].tet = static_cast<int32_t>(s.mesh.tets.size());
  EXPECT_EQ(evaluateEmbedded(s.mesh.tets, s.mesh.vertices, embedding, &positions), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find("point 1 refers to tet"), std::string::npos) << lastError();
  EXPECT_EQ(computeVertexNormals({{0, 0, 0}}, {{{0, 0, 1}}}, &positions), Status::InvalidArgument);
}

// ~100K tets and 100K points: checks the grid keeps this interactive (the time is recorded,
// not asserted: timings belong in benchmarks) and spot-checks against brute force.
TEST(GeometryEmbedding, LargeMesh) {
  const SphereMesh s = voxelSphere(30);
  ASSERT_GT(s.mesh.tets.size(), 80000u);
  Array<Eigen::Vector3d> points = randomPointsInBall(100000, 1.2, 3);
  Array<EmbeddedPoint> embedding;
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(embedPoints(s.mesh, points, &embedding), Status::Ok) << lastError();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ::testing::Test::RecordProperty("embed_ms", std::to_string(ms));
  for (size_t i = 0; i < points.size(); i += 12497) {
    double nearest = INFINITY;
    for (size_t t = 0; t < s.mesh.tets.size(); ++t)
      nearest = std::min(nearest, pointTetDistance(s.mesh, static_cast<int32_t>(t), points[i]));
    EXPECT_EQ(pointTetDistance(s.mesh, embedding[i].tet, points[i]), nearest) << i;
    if (nearest == 0.0) {
      EXPECT_GE(minCoordinate(embedding[i]), -kRoundOff) << i;
    }
  }
}

}  // namespace
}  // namespace vp

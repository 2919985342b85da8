// validateAndRepairTetMesh: each bad input is rejected with a message naming the index and
// value and leaves the mesh untouched; each repairable defect is repaired and counted.
#include "geometry/tet_mesh_validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace vp {
namespace {

// Two positively oriented tets sharing the face (1, 2, 3).
TetMesh twoTets() {
  TetMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  mesh.tets = {{{0, 1, 2, 3}}, {{1, 4, 2, 3}}};
  return mesh;
}

bool sameMesh(const TetMesh& a, const TetMesh& b) {
  if (a.tets != b.tets || a.vertices.size() != b.vertices.size()) return false;
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    // Bitwise comparison so that a NaN coordinate compares equal to itself.
    if (std::memcmp(a.vertices[i].data(), b.vertices[i].data(), sizeof(double) * 3) != 0) return false;
  }
  return true;
}

void expectRejected(TetMesh mesh, const std::string& fragment) {
  const TetMesh before = mesh;
  TetMeshRepairReport report;
  report.invertedTetsFixed = 42;
  EXPECT_EQ(validateAndRepairTetMesh(mesh, &report), Status::InvalidArgument);
  EXPECT_NE(std::string(lastError()).find(fragment), std::string::npos) << lastError();
  EXPECT_TRUE(sameMesh(before, mesh));
  EXPECT_EQ(report.invertedTetsFixed, 42);  // the report is only written on success
}

TEST(GeometryValidation, ValidMeshPassesUnchanged) {
  TetMesh mesh = twoTets();
  ASSERT_GT(signedTetVolume(mesh, 0), 0.0);
  ASSERT_GT(signedTetVolume(mesh, 1), 0.0);
  TetMeshRepairReport report;
  ASSERT_EQ(validateAndRepairTetMesh(mesh, &report), Status::Ok) << lastError();
  EXPECT_TRUE(sameMesh(twoTets(), mesh));
  EXPECT_EQ(report.invertedTetsFixed, 0);
  EXPECT_EQ(report.unusedVerticesRemoved, 0);
  EXPECT_EQ(report.newIndexOfOldVertex, (Array<int32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(validateAndRepairTetMesh(mesh, nullptr), Status::Ok);
}

TEST(GeometryValidation, RejectsEmpty) {
  TetMesh mesh = twoTets();
  mesh.tets.clear();
  expectRejected(mesh, "no tets");
  expectRejected(TetMesh{}, "no vertices");
}

TEST(GeometryValidation, RejectsNonFiniteCoordinates) {
  TetMesh mesh = twoTets();
  mesh.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  expectRejected(mesh, "vertex 3 has a non-finite coordinate y = nan");
  mesh = twoTets();
  mesh.vertices[4].z() = -std::numeric_limits<double>::infinity();
  expectRejected(mesh, "vertex 4 has a non-finite coordinate z = -inf");
}

TEST(GeometryValidation, RejectsBadIndices) {
  TetMesh mesh = twoTets();
  mesh.tets[1][2] = 5;
  expectRejected(mesh, "tet 1 corner 2 is vertex 5, outside [0, 5)");
  mesh = twoTets();
  mesh.tets[0][0] = -1;
  expectRejected(mesh, "tet 0 corner 0 is vertex -1");
  mesh = twoTets();
  mesh.tets[1] = {{1, 4, 2, 4}};
  expectRejected(mesh, "tet 1 uses vertex 4 twice (corners 1 and 3)");
}

TEST(GeometryValidation, RejectsDegenerateTets) {
  // Tet 1 flattened into the plane x + y + z = 1 of the shared face.
  TetMesh mesh = twoTets();
  mesh.vertices[4] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  expectRejected(mesh, "tet 1 is degenerate");

  // Just above / below the relative tolerance: lift a vertex off the face plane so that
  // the volume is 1e-10 L^3 times 10 or times 0.1 (L = mean edge length).
  auto liftedMesh = [](double factor) {
    TetMesh m = twoTets();
    const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 1).normalized();
    const Eigen::Vector3d centroid(1.0 / 3, 1.0 / 3, 1.0 / 3);
    m.vertices[4] = centroid;
    // Find L with the vertex in its final place (L barely changes with the lift).
    const double edge = meanTetEdgeLength(m);
    const double faceArea = 0.5 * std::sqrt(3.0);
    const double height = factor * kDegenerateVolumeTolerance * edge * edge * edge * 3.0 / faceArea;
    m.vertices[4] = centroid + height * n;
    return m;
  };
  TetMesh thin = liftedMesh(0.1);
  expectRejected(thin, "tet 1 is degenerate");
  TetMesh ok = liftedMesh(10.0);
  EXPECT_EQ(validateAndRepairTetMesh(ok, nullptr), Status::Ok) << lastError();

  // The tolerance is relative: the same shapes scaled by 1e-4 (tiny units) still pass.
  TetMesh small = twoTets();
  for (auto& v : small.vertices) v *= 1e-4;
  EXPECT_EQ(validateAndRepairTetMesh(small, nullptr), Status::Ok) << lastError();
}

TEST(GeometryValidation, RepairsInvertedTets) {
  TetMesh mesh = twoTets();
  std::swap(mesh.tets[1][0], mesh.tets[1][1]);  // odd permutation: negative volume
  const double volumeBefore = std::fabs(signedTetVolume(mesh, 1));
  ASSERT_LT(signedTetVolume(mesh, 1), 0.0);
  TetMeshRepairReport report;
  ASSERT_EQ(validateAndRepairTetMesh(mesh, &report), Status::Ok) << lastError();
  EXPECT_EQ(report.invertedTetsFixed, 1);
  EXPECT_EQ(report.unusedVerticesRemoved, 0);
  EXPECT_DOUBLE_EQ(signedTetVolume(mesh, 1), volumeBefore);
  EXPECT_EQ(mesh.tets[0], twoTets().tets[0]);  // untouched
  EXPECT_EQ(mesh.tets[1], (std::array<int32_t, 4>{{4, 1, 3, 2}}));
}

TEST(GeometryValidation, RemovesUnusedVerticesAndRemaps) {
  TetMesh mesh = twoTets();
  // Unused vertices before, between and after the used ones; one is NaN-free junk.
  mesh.vertices.insert(mesh.vertices.begin(), Eigen::Vector3d(9, 9, 9));
  mesh.vertices.insert(mesh.vertices.begin() + 3, Eigen::Vector3d(8, 8, 8));
  mesh.vertices.emplace_back(7, 7, 7);
  // old: 0 junk, 1 v0, 2 v1, 3 junk, 4 v2, 5 v3, 6 v4, 7 junk
  mesh.tets = {{{1, 2, 4, 5}}, {{2, 6, 4, 5}}};
  TetMeshRepairReport report;
  ASSERT_EQ(validateAndRepairTetMesh(mesh, &report), Status::Ok) << lastError();
  EXPECT_EQ(report.unusedVerticesRemoved, 3);
  EXPECT_EQ(report.invertedTetsFixed, 0);
  EXPECT_EQ(report.newIndexOfOldVertex, (Array<int32_t>{-1, 0, 1, -1, 2, 3, 4, -1}));
  EXPECT_TRUE(sameMesh(twoTets(), mesh));
}

}  // namespace
}  // namespace vp

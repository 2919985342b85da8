// Dihedral angles and volumes of geometry/mesh_quality.h against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/box_tet_mesh.h"
#include "geometry/mesh_quality.h"
#include "geometry/tet_mesh_boundary.h"

namespace vp {
namespace {

TEST(MeshQuality, KuhnCubesHaveDihedralsFrom45To90AndTheBoxsVolume) {
  const TetMesh box = makeBoxTetMesh({3, 2, 2}, Vec3(1.5, 1.0, 1.0), Vec3(-1, 2, 0));
  const TetMeshQuality q = tetMeshQuality(box, tetMeshBoundary(box));
  EXPECT_NEAR(q.minDihedralDegrees, 45.0, 1e-9);
  EXPECT_NEAR(q.maxDihedralDegrees, 90.0, 1e-9);
  EXPECT_NEAR(q.tetVolume, 1.5, 1e-12);
  EXPECT_NEAR(q.surfaceVolume, 1.5, 1e-12);  // its own boundary, away from the origin
}

TEST(MeshQuality, ARegularTetAndASliver) {
  TetMesh regular;
  regular.vertices = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  regular.tets = {{0, 1, 2, 3}};
  if (signedTetVolume(regular, 0) < 0) std::swap(regular.tets[0][2], regular.tets[0][3]);
  const TetMeshQuality q = tetMeshQuality(regular, tetMeshBoundary(regular));
  const double expected = std::acos(1.0 / 3.0) * 180.0 / M_PI;
  EXPECT_NEAR(q.minDihedralDegrees, expected, 1e-9);
  EXPECT_NEAR(q.maxDihedralDegrees, expected, 1e-9);
  EXPECT_NEAR(q.tetVolume, 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(q.surfaceVolume, 8.0 / 3.0, 1e-12);
  // Four nearly coplanar corners of a square, two lifted a little: angles near 0 and 180.
  TetMesh sliver;
  sliver.vertices = {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 0.01), Vec3(0, 1, 0.01)};
  sliver.tets = {{0, 1, 2, 3}};
  if (signedTetVolume(sliver, 0) < 0) std::swap(sliver.tets[0][2], sliver.tets[0][3]);
  const TetMeshQuality s = tetMeshQuality(sliver, tetMeshBoundary(sliver));
  EXPECT_LT(s.minDihedralDegrees, 3.0);
  EXPECT_GT(s.maxDihedralDegrees, 177.0);
}

}  // namespace
}  // namespace vp

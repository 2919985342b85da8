// Lattice node signs against a closed mesh by crossings along lattice lines: where they
// decide, they are the signs of the mesh's signed distance at every node; where a node lies on
// the surface, they do not decide.
#include "collide/mesh_lattice_signs.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace vp {
namespace {

// A box mesh with half extents `he`, turned by `rotation` about its centre `centre`.
void addBox(const Eigen::Vector3d& he, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& centre,
            ColliderShape* s) {
  const int base = static_cast<int>(s->meshVertices.size());
  for (int c = 0; c < 8; ++c)
    s->meshVertices.push_back(centre + rotation * Eigen::Vector3d(c & 1 ? he.x() : -he.x(), c & 2 ? he.y() : -he.y(),
                                                                  c & 4 ? he.z() : -he.z()));
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    s->meshTriangles.emplace_back(base + q[0], base + q[1], base + q[2]);
    s->meshTriangles.emplace_back(base + q[0], base + q[2], base + q[3]);
  }
}

// The signs the split cut-cell pass read before: the signed distance at every node.
std::array<uint64_t, 8> outsideBySignedDistance(const PreparedCollider& mesh, const Eigen::Vector3d& origin, double h,
                                                const Eigen::Vector3d& cell) {
  std::array<uint64_t, 8> out{};
  for (int c = 0; c < 8; ++c)
    for (int b = 0; b < 8; ++b)
      for (int a = 0; a < 8; ++a)
        if (signedDistanceBound(mesh, origin + h * (cell + Eigen::Vector3d(a, b, c) / 7)) > 0.0)
          out[static_cast<size_t>(c)] |= uint64_t(1) << (a + 8 * b);
  return out;
}

TEST(MeshLatticeSigns, EqualTheSignedDistanceSignsAroundASlantedPlateAndACube) {
  // A plate thinner than a cell (it passes between lattice nodes) and a cube in one mesh: not
  // convex, with cells the plate splits.
  ColliderShape shape;
  shape.kind = ShapeKind::TriangleMesh;
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.43, Eigen::Vector3d(1.0, 0.3, 0.7).normalized()).toRotationMatrix();
  addBox(Eigen::Vector3d(0.6, 0.02, 0.5), turn, Eigen::Vector3d(0.013, 0.021, -0.017), &shape);
  addBox(Eigen::Vector3d(0.2, 0.25, 0.15), turn.transpose(), Eigen::Vector3d(0.3, 0.45, 0.1), &shape);
  PreparedCollider mesh;
  ASSERT_EQ(prepareCollider(shape, &mesh), Status::Ok);
  const Eigen::Vector3d origin(-0.8, -0.8, -0.8);
  const double h = 0.1;
  int decided = 0, mixed = 0;
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) {
        const Eigen::Vector3d cell(i, j, k);
        std::array<uint64_t, 8> outside;
        if (!latticeNodesOutsideMesh(mesh, origin, h, cell, &outside)) continue;
        ++decided;
        const std::array<uint64_t, 8> expected = outsideBySignedDistance(mesh, origin, h, cell);
        ASSERT_EQ(outside, expected) << "cell " << i << ", " << j << ", " << k;
        bool anyIn = false, anyOut = false;
        for (uint64_t layer : expected) anyIn = anyIn || layer != ~uint64_t(0), anyOut = anyOut || layer != 0;
        mixed += anyIn && anyOut;
      }
  // Generic positions: every cell decides, and hundreds hold both signs.
  EXPECT_EQ(decided, 16 * 16 * 16);
  EXPECT_GT(mixed, 200);
}

TEST(MeshLatticeSigns, DecideAroundAnAlignedCubeExceptWhereNodesLieOnItsFaces) {
  // Faces parallel to the lattice lines: the lines beside a face pass it, the lines through it
  // cross it. Nodes on a face are not open (signed distance 0), which crossings cannot tell.
  ColliderShape shape;
  shape.kind = ShapeKind::TriangleMesh;
  addBox(Eigen::Vector3d(0.25, 0.25, 0.25), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), &shape);
  PreparedCollider mesh;
  ASSERT_EQ(prepareCollider(shape, &mesh), Status::Ok);
  const double h = 0.125;
  // Offsets that put no node on a face or on a face's diagonal (y == z, x == z, ...).
  const Eigen::Vector3d origin(-0.53, -0.517, -0.541);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d cell(i, j, k);
        std::array<uint64_t, 8> outside;
        ASSERT_TRUE(latticeNodesOutsideMesh(mesh, origin, h, cell, &outside)) << "cell " << i << ", " << j << ", " << k;
        ASSERT_EQ(outside, outsideBySignedDistance(mesh, origin, h, cell)) << "cell " << i << ", " << j << ", " << k;
      }
  // Lattice planes through the faces: the cell whose high x-side lies on the face x = -0.25.
  std::array<uint64_t, 8> outside;
  EXPECT_FALSE(latticeNodesOutsideMesh(mesh, Eigen::Vector3d::Constant(-0.5), h, Eigen::Vector3d(1, 3, 3), &outside));
}

}  // namespace
}  // namespace vp

// The BB node numbering of a mesh (deform/bb_node_numbering.h): counts from the mesh's edges
// and faces, nodes shared exactly across the shared face, control points where the element
// puts them, and each control point's support.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "deform/bb_multi_index.h"
#include "deform/bb_node_numbering.h"

namespace vp {
namespace {

// Two positively oriented tets sharing the face (0, 1, 2): 5 vertices, 9 edges, 7 faces.
TetMesh twoTets() {
  TetMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  m.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  return m;
}

std::set<int32_t> nodesOf(const BBNodeNumbering& n, int element, int N) {
  return std::set<int32_t>(n.elementNodes.begin() + N * element, n.elementNodes.begin() + N * (element + 1));
}

TEST(BBNodeNumbering, CountsNodesPerVertexEdgeAndFace) {
  const TetMesh mesh = twoTets();
  // Degree 1: the vertices; 2: plus one per edge; 3: plus two per edge and one per face.
  const int expected[4] = {0, 5, 5 + 9, 5 + 2 * 9 + 7};
  for (int degree = 1; degree <= 3; ++degree) {
    BBNodeNumbering n;
    ASSERT_EQ(numberBBNodes(mesh, degree, &n), Status::Ok) << degree;
    EXPECT_EQ(n.nodeCount, expected[degree]) << degree;
    EXPECT_EQ(n.restPositions.size(), static_cast<size_t>(n.nodeCount));
    EXPECT_EQ(n.support.size(), static_cast<size_t>(n.nodeCount));
    EXPECT_EQ(n.elementNodes.size(), static_cast<size_t>(2 * bbNodeCount(degree)));
  }
}

TEST(BBNodeNumbering, TheTetsShareExactlyTheNodesOfTheirCommonFace) {
  const TetMesh mesh = twoTets();
  for (int degree = 1; degree <= 3; ++degree) {
    BBNodeNumbering n;
    ASSERT_EQ(numberBBNodes(mesh, degree, &n), Status::Ok);
    const int N = bbNodeCount(degree);
    const std::set<int32_t> a = nodesOf(n, 0, N), b = nodesOf(n, 1, N);
    std::vector<int32_t> shared;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
    // A triangle of degree n has (n + 1)(n + 2) / 2 control points.
    EXPECT_EQ(shared.size(), static_cast<size_t>((degree + 1) * (degree + 2) / 2)) << degree;
    // Each element's nodes are distinct.
    EXPECT_EQ(a.size(), static_cast<size_t>(N));
    EXPECT_EQ(b.size(), static_cast<size_t>(N));
    // The shared ones lie on the face z = 0.
    for (int32_t s : shared) EXPECT_NEAR(n.restPositions[s].z(), 0.0, 1e-15) << degree;
  }
}

TEST(BBNodeNumbering, ControlPointsSitOnTheirSupportAtTheirBarycentre) {
  BBNodeNumbering n;
  ASSERT_EQ(numberBBNodes(twoTets(), 2, &n), Status::Ok);
  for (int32_t i = 0; i < n.nodeCount; ++i) {
    const auto& s = n.support[i];
    if (i < 5) {
      EXPECT_EQ(s[0], -1) << i;  // a vertex node
      continue;
    }
    // Quadratic: every added node is an edge's midpoint.
    ASSERT_GE(s[0], 0);
    ASSERT_GE(s[1], 0);
    EXPECT_EQ(s[2], -1) << i;
    const Vec3 mid = 0.5 * (n.restPositions[s[0]] + n.restPositions[s[1]]);
    EXPECT_NEAR((n.restPositions[i] - mid).norm(), 0.0, 1e-15) << i;
  }
}

}  // namespace
}  // namespace vp

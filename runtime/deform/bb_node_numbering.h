// The nodes of a tet mesh of Bernstein-Bezier elements of one degree: the mesh's vertices keep
// their indices; for degree > 1 the edge and face control points follow, one per BB node key
// (bb_multi_index.h), so that the tets around an edge or face share its nodes, numbered in
// order of first appearance (element by element, each in BB local order).
#pragma once

#include <array>
#include <cstdint>

#include "core/allocator.h"
#include "core/math_types.h"
#include "core/status.h"
#include "geometry/tet_mesh.h"

namespace vp {

struct BBNodeNumbering {
  int32_t nodeCount = 0;
  Array<int32_t> elementNodes;  // bbNodeCount(degree) per element, BB local order
  Array<Vec3> restPositions;    // per node: the control point at rest
  // Per node: the mesh vertices an edge or face control point lies on (-1: unused; all -1
  // for a vertex node). Such a node is on the boundary, or pinned, when they all are.
  Array<std::array<int32_t, 3>> support;
};

// `mesh` must be valid (degree 1..3); errors are bbNodeKey's and bbRestNodePositions'.
Status numberBBNodes(const TetMesh& mesh, int degree, BBNodeNumbering* out);

}  // namespace vp

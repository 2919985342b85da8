// The levels of p-multigrid: one tet mesh seen at several BB degrees (e.g. 3 -> 2 -> 1), and
// the prolongations between consecutive levels by degree elevation.
//
// Node numbering at every level follows the deformable actor's rule: the mesh vertices
// first, with their own indices, then each edge/face control point in the order the tets
// first reach it. So vertex v is node v at every degree, and the degree-1 level is exactly
// the linear mesh (its positions are the first 3V entries of the fine positions).
//
// Prolongation from degree c to degree f (f > c, also f = c + 2): per element, the local
// elevation matrix (bbElevationRows composed); a fine node gets its row from the first
// element that owns it. Elevation of a continuous field is continuous (a fine node on an
// edge or face only reads coarse nodes on that edge or face), so every owner gives the same
// row and nothing needs averaging.
#pragma once

#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "linalg/node_prolongation.h"

namespace vp {

struct DegreeLevel {
  int degree = 1;
  int32_t nodeCount = 0;
  Array<int32_t> elementNodes;  // bbNodeCount(degree) per element, BB local order
};

struct DegreeHierarchy {
  std::vector<DegreeLevel> levels;            // finest first
  std::vector<NodeProlongation> prolongations;  // [l]: levels[l + 1] -> levels[l]
};

// fineNodes: bbNodeCount(degrees[0]) per element, vertices first in each element (the
// actor's elementNodes). degrees: strictly decreasing, starting at the fine degree, each
// 1..3 (e.g. {3, 2, 1}, {3, 1}, {2, 1}). Fails with InvalidArgument otherwise.
Status buildDegreeHierarchy(const std::vector<int>& degrees, const int32_t* fineNodes, int64_t elementCount,
                            int32_t fineNodeCount, DegreeHierarchy* out);

}  // namespace vp

// Colours elements so that no two elements of one colour share a node. Elements of one
// colour can then scatter into the global matrix and force vector in parallel without
// atomics, and the sum order (colour by colour) is fixed, so assembly is deterministic for
// any worker count. Greedy in element order: deterministic, typically 20-40 colours for tets.
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.h"

namespace vp {

struct ElementColoring {
  std::vector<int32_t> colorStart;  // colour c owns order[colorStart[c] .. colorStart[c+1])
  std::vector<int32_t> order;       // element indices grouped by colour
  int colorCount() const { return static_cast<int>(colorStart.size()) - 1; }
};

Status colorElements(int32_t nodeCount, const int32_t* elementNodes, int64_t elementCount, int nodesPerElement,
                     ElementColoring* out);

}  // namespace vp

#include "deform/element_incidence.h"

#include <vector>

namespace vp {

void ElementIncidence::build(int32_t nodeCount, const int32_t* elementNodes, int64_t elementCount,
                             int nodesPerElement) {
  const int64_t entries = nodesPerElement * elementCount;
  start.assign(static_cast<size_t>(nodeCount) + 1, 0);
  for (int64_t k = 0; k < entries; ++k) start[elementNodes[k] + 1]++;
  for (int32_t i = 0; i < nodeCount; ++i) start[i + 1] += start[i];
  element.resize(static_cast<size_t>(entries));
  corner.resize(static_cast<size_t>(entries));
  Array<int32_t> fill(start.begin(), start.end() - 1);
  for (int64_t k = 0; k < entries; ++k) {
    const int32_t slot = fill[elementNodes[k]]++;
    element[slot] = static_cast<int32_t>(k / nodesPerElement);
    corner[slot] = static_cast<uint8_t>(k % nodesPerElement);
  }
}

}  // namespace vp

// Node -> (element, local corner) incidence of an element mesh, grouped by node and in
// element order within a node: what a gather assembly walks to write each matrix row once
// (one task per row, no atomics, a fixed summation order).
//
// Arrays: elementNodes holds nodesPerElement global node ids per element; node i's pairs are
// (element[k], corner[k]) for k in [start[i], start[i + 1]).
#pragma once

#include <cstdint>

#include "core/allocator.h"

namespace vp {

struct ElementIncidence {
  Array<int32_t> start;    // nodeCount + 1
  Array<int32_t> element;  // nodesPerElement * elementCount
  Array<uint8_t> corner;

  void build(int32_t nodeCount, const int32_t* elementNodes, int64_t elementCount, int nodesPerElement);
};

}  // namespace vp

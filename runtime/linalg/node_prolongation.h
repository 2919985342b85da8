// A prolongation that acts per node with scalar weights (the same for x, y and z):
// fine node i = Σ_k weights[k] · coarse node columns[k], k in [rowStart[i], rowStart[i+1]).
// p-multigrid's degree elevation has this form; its transpose is the restriction.
#pragma once

#include "core/allocator.h"

#include <cstdint>
#include <vector>

namespace vp {

struct NodeProlongation {
  int32_t fineNodes = 0, coarseNodes = 0;
  Array<int32_t> rowStart;  // fineNodes + 1
  Array<int32_t> columns;
  Array<double> weights;
};

}  // namespace vp

// One node's row of a gather assembly, as a kernel body a CPU task and a CUDA thread run alike:
// each row is written by exactly one caller, so no atomics are needed and the sum order is
// fixed (deterministic for any worker count, and the same on the device).
//
// Arrays: rowStart (BCSR, nodes + 1) and values (9 per block, row-major); the node -> (element,
// corner) incidence grouped by node (runtime/deform/element_incidence.h); scatter, per element
// N x N block indices into values (block (a, b) at N*N*e + N*a + b); elementForce, 3 per
// element corner (N per element).
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

struct ElementIncidenceView {
  const int32_t* start = nullptr;    // nodes + 1
  const int32_t* element = nullptr;  // per (element, corner) pair
  const uint8_t* corner = nullptr;
};

// Zeroes row i's blocks, then adds every incident element's force at the node's corner a into
// force[3 i ..] and, through addBlock(e, a, b, block), its block (a, b) into the matrix.
template <class AddBlock>
VP_HOST_DEVICE inline void gatherElementRow(int64_t i, int nodesPerElement, const int32_t* rowStart,
                                            const ElementIncidenceView& incidence, const int32_t* scatter,
                                            const double* elementForce, const AddBlock& addBlock, double* values,
                                            double* force) {
  const int N = nodesPerElement;
  for (int32_t k = rowStart[i]; k < rowStart[i + 1]; ++k)
    for (int c = 0; c < 9; ++c) values[9 * static_cast<int64_t>(k) + c] = 0.0;
  double f[3] = {0.0, 0.0, 0.0};
  for (int32_t k = incidence.start[i]; k < incidence.start[i + 1]; ++k) {
    const int64_t e = incidence.element[k];
    const int a = incidence.corner[k];
    for (int c = 0; c < 3; ++c) f[c] += elementForce[3 * (N * e + a) + c];
    for (int b = 0; b < N; ++b) addBlock(e, a, b, &values[9 * static_cast<int64_t>(scatter[N * N * e + N * a + b])]);
  }
  for (int c = 0; c < 3; ++c) force[3 * i + c] = f[c];
}

}  // namespace vp::kernels

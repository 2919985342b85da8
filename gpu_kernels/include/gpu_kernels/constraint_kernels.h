// The deformables' node constraints as a projection (deform/node_constraints.h holds the rule):
// a fixed node keeps none of a vector's components, a sliding contact only those across its
// normal n (v - (v . n) n), a free node all. Written once for the CPU's filter and the CUDA CG.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

enum NodeConstraintKind : uint8_t { kNodeFree = 0, kNodeFixed = 1, kNodeContact = 2 };

// Component c of the filtered v = (v0, v1, v2) at a node of this kind and normal.
VP_HOST_DEVICE inline double filteredComponent(uint8_t kind, const double* normal, double v0, double v1, double v2,
                                               int c) {
  const double vc = c == 0 ? v0 : c == 1 ? v1 : v2;  // not an array: it would live in memory on the device
  if (kind == kNodeFixed) return 0.0;
  if (kind != kNodeContact) return vc;
  const double along = v0 * normal[0] + v1 * normal[1] + v2 * normal[2];
  return vc - along * normal[c];
}

// Filters node i's three components of vec in place.
VP_HOST_DEVICE inline void filterNode(int64_t i, const uint8_t* kind, const double* normal, double* vec) {
  double* vi = vec + 3 * i;
  const double v0 = vi[0], v1 = vi[1], v2 = vi[2];
  for (int c = 0; c < 3; ++c) vi[c] = filteredComponent(kind[i], normal + 3 * i, v0, v1, v2, c);
}

}  // namespace vp::kernels

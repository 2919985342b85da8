// A MAC grid's layout as kernel bodies see it (runtime/fluid/mac_grid.h has the grid): cell
// counts, which domain sides are Walls, and the cell and face indices.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

// Walls in MacGrid::sides order: -x, +x, -y, +y, -z, +z.
struct MacLayout {
  int64_t nx, ny, nz;
  bool wall[6];

  VP_HOST_DEVICE int64_t cells(int a) const { return a == 0 ? nx : a == 1 ? ny : nz; }
  VP_HOST_DEVICE int64_t cellIndex(int64_t i, int64_t j, int64_t k) const { return i + nx * (j + ny * k); }
  VP_HOST_DEVICE int64_t faceIndex(int a, int64_t i, int64_t j, int64_t k) const {
    return i + (nx + (a == 0)) * (j + (ny + (a == 1)) * k);
  }
  // Whether a-face number `along` (0 .. cells(a)) lies on a domain Wall side.
  VP_HOST_DEVICE bool isWall(int a, int64_t along) const {
    return (along == 0 && wall[2 * a]) || (along == cells(a) && wall[2 * a + 1]);
  }
};

}  // namespace vp::kernels

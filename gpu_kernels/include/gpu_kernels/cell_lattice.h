// The cells of a grid as kernel bodies index them: cell (i, j, k) is i + nx (j + ny k).
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

struct CellLattice {
  int n[3];
  int64_t stride[3];  // 1, nx, nx ny
  double h;

  VP_HOST_DEVICE void coordinates(int64_t c, int64_t ijk[3]) const {
    ijk[0] = c % n[0];
    ijk[1] = (c / n[0]) % n[1];
    ijk[2] = c / stride[2];
  }
};

}  // namespace vp::kernels

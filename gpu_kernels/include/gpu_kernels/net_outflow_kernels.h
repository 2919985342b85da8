// Kernel body of the pressure projection's right-hand side (runtime/fluid/pressure/
// cut_cell_poisson.h, computeNetOutflow): one cell's net outflow through its six faces, the open
// part of each face carrying the fluid's velocity and the covered part the solid's.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/pressure_update_kernels.h"

namespace vp::kernels {

// What every cell reads: per axis the faces' open fractions, solids' normal velocities and the
// fluid's velocity (MAC layouts), and the grid's layout.
struct NetOutflowFields {
  const double* open[3];
  const double* solidVelocity[3];
  const double* velocity[3];
  MacLayout grid;
};

// Sum over cell (i, j, k)'s faces, -x, +x, -y, +y, -z, +z in turn, of the flux out of it. A
// domain Wall face stops the fluid but not a collider reaching through it (its covered part
// carries the collider's velocity); other faces count open fractions below kMinOpenFraction as
// closed. The caller writes 0 on cells that are not fluid.
VP_HOST_DEVICE inline double netOutflowCell(const NetOutflowFields& in, int64_t i, int64_t j, int64_t k) {
  double sum = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int high = 0; high < 2; ++high) {
      int64_t face[3] = {i, j, k};
      face[a] += high;
      const bool wall = in.grid.isWall(a, face[a]);
      const int64_t f = in.grid.faceIndex(a, face[0], face[1], face[2]);
      const double raw = in.open[a][f];
      const double open = wall ? (raw < 0.0 ? 0.0 : raw > 1.0 ? 1.0 : raw) : openedFraction(raw);
      const double fluidVelocity = wall ? 0.0 : in.velocity[a][f];
      const double flux = open * fluidVelocity + (1.0 - open) * in.solidVelocity[a][f];
      sum += high ? flux : -flux;
    }
  return sum;
}

}  // namespace vp::kernels

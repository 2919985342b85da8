// Kernel bodies of the cut-cell multigrid's coarsening (runtime/fluid/pressure/
// multigrid_coarsening.h has the rules and their reasons): a fine column's conductance under a
// coarse face, a coarse cell's free-surface term and its diagonal. Functions of an index and
// plain arrays (grids as MacLayout, whose wall flags they do not read); the CPU's passes
// (multigrid_coarsening.cpp) call them per value or, for the column conductances, in row loops
// that compute the same operations for a whole row.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/mac_layout.h"
#include "gpu_kernels/pressure_update_kernels.h"

namespace vp::kernels {

// A fine column under a coarse face, from the centre of one coarse cell to the other's: half of
// the fine face behind it in the low coarse cell, the shared face, half of the one behind it in
// the high coarse cell, in series. Where the high coarse cell has a single child along the axis
// the column ends at the shared face. Closed faces (0) give inf / 0 here; callers add the term
// only where every face of the column is open.
VP_HOST_DEVICE inline double seriesConductance(double low, double shared, double high) {
  return 2.0 / (0.5 / low + 1.0 / shared + 0.5 / high);
}
VP_HOST_DEVICE inline double endConductance(double low, double shared) { return 1.5 / (0.5 / low + 1.0 / shared); }

// Sum of values[child] over the children of coarse cell (I, J, K) that exist on the fine grid
// `fine` (k outer, then j, then i).
VP_HOST_DEVICE inline double sumOverChildren(const MacLayout& fine, const double* values, int64_t I, int64_t J,
                                             int64_t K) {
  double sum = 0.0;
  for (int64_t k = 2 * K; k < 2 * K + 2 && k < fine.nz; ++k)
    for (int64_t j = 2 * J; j < 2 * J + 2 && j < fine.ny; ++j)
      for (int64_t i = 2 * I; i < 2 * I + 2 && i < fine.nx; ++i) sum += values[fine.cellIndex(i, j, k)];
  return sum;
}

// What a coarse cell's free-surface term reads: per coarse cell the children's mean level set
// and whether any child is fluid, per coarse face its open fraction; per fine cell the fine
// free-surface terms.
struct CoarseSurfaceFields {
  MacLayout coarse, fine;
  const double* liquidPhi;
  const uint8_t* fluid;
  const double* openFraction[3];
  const double* fineSurface;
};

// The free-surface part of coarse cell (I, J, K)'s diagonal: on each open face towards a coarse
// cell without fluid children, A_F / theta from the two cells' mean level sets (a fluid cell
// whose centre lies in the air takes the smallest theta; a liquid neighbour mean without fluid
// children is air over solid, the surface at its centre). Without such a face, the halved sum
// of the children's terms. 0 off fluid.
VP_HOST_DEVICE inline double coarseSurfaceTerm(const CoarseSurfaceFields& in, int64_t I, int64_t J, int64_t K) {
  const MacLayout& c = in.coarse;
  const int64_t cell = c.cellIndex(I, J, K);
  if (!in.fluid[cell]) return 0.0;
  const double phi = in.liquidPhi[cell];
  double surface = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      int64_t nb[3] = {I, J, K};
      nb[a] += side == 0 ? -1 : 1;
      if (nb[a] < 0 || nb[a] >= c.cells(a)) continue;
      const int64_t nbCell = c.cellIndex(nb[0], nb[1], nb[2]);
      if (in.fluid[nbCell]) continue;
      int64_t high[3] = {I, J, K};
      high[a] += side;
      const double open = in.openFraction[a][c.faceIndex(a, high[0], high[1], high[2])];
      if (!(open > 0.0)) continue;
      const double phiNb = in.liquidPhi[nbCell];
      const double theta = !isLiquid(phi) ? kMinFreeSurfaceTheta : isLiquid(phiNb) ? 1.0 : freeSurfaceTheta(phi, phiNb);
      surface += open / theta;
    }
  // surface is 0 here, or NaN, which the sum keeps.
  if (!(surface > 0.0)) surface = 0.5 * (surface + sumOverChildren(in.fine, in.fineSurface, I, J, K));
  return surface;
}

// Coarse cell (i, j, k)'s diagonal: its six faces' couplings (low then high face per axis, x,
// y, z) plus its Dirichlet part.
VP_HOST_DEVICE inline double coarseDiagonalAt(const MacLayout& c, const double* const coupling[3], double dirichlet,
                                              int64_t i, int64_t j, int64_t k) {
  double sum = 0.0;
  for (int a = 0; a < 3; ++a) {
    int64_t hi[3] = {i, j, k};
    ++hi[a];
    sum += coupling[a][c.faceIndex(a, i, j, k)];
    sum += coupling[a][c.faceIndex(a, hi[0], hi[1], hi[2])];
  }
  return sum + dirichlet;
}

}  // namespace vp::kernels

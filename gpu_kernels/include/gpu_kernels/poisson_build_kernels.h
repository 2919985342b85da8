// Kernel bodies of the cut-cell pressure operator's build (runtime/fluid/pressure/
// cut_cell_poisson.h): one interior face's coupling and open fraction, and one cell's diagonal
// with its free-surface part, from the colliders' open fractions and, for a liquid, the level
// set. Each face and cell is written once from inputs only, so they may run in any order or
// concurrently.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/mac_layout.h"
#include "gpu_kernels/pressure_update_kernels.h"

namespace vp::kernels {

// What every face and cell reads: per axis the faces' collider open fractions (MAC layouts),
// the level set per cell (nullptr for smoke) and the grid's layout.
struct PoissonBuildFields {
  const double* open[3];
  const double* liquidPhi;
  MacLayout grid;
};

struct FaceCoupling {
  double coupling;  // A_f between two cells with rows, else 0
  double open;      // A_f whatever the level set (the free-surface operator keeps it)
};

// Face f of axis a between cells lowCell and highCell, neither on a domain side: its open
// fraction (below kMinOpenFraction: closed); with a free surface only liquid-liquid faces
// couple, a liquid-air face being a term of the liquid cell's diagonal (cellDiagonalAt).
VP_HOST_DEVICE inline FaceCoupling interiorFaceCoupling(const PoissonBuildFields& in, int a, int64_t f,
                                                        int64_t lowCell, int64_t highCell) {
  const double open = openedFraction(in.open[a][f]);
  const bool liquidBoth =
      in.liquidPhi == nullptr || (isLiquid(in.liquidPhi[highCell]) && isLiquid(in.liquidPhi[lowCell]));
  return FaceCoupling{liquidBoth ? open : 0.0, open};
}

struct CellDiagonal {
  double diagonal;  // sum over the open faces of A_f, or A_f / theta towards air
  double surface;   // the free-surface terms of it
  bool air;         // a level-set air cell with an open face (0 diagonal)
};

// The diagonal of cell c from its six faces' open fractions, -x, +x, -y, +y, -z, +z in turn
// (summed in that order), and the cell across each (-1 beyond a domain side: an Open side's
// face is a Dirichlet term, a Wall's is closed, so its open fraction is 0 here).
VP_HOST_DEVICE inline CellDiagonal diagonalFromFaces(const PoissonBuildFields& in, int64_t c, const double open[6],
                                                     const int64_t neighbour[6]) {
  CellDiagonal out{0.0, 0.0, false};
  if (in.liquidPhi != nullptr && !isLiquid(in.liquidPhi[c])) {
    for (int f = 0; f < 6; ++f) out.air = out.air || open[f] > 0.0;
    return out;  // air: p = 0, no row
  }
  for (int f = 0; f < 6; ++f) {
    if (in.liquidPhi != nullptr && open[f] > 0.0 && neighbour[f] >= 0) {
      const double phiNb = in.liquidPhi[neighbour[f]];
      if (!isLiquid(phiNb)) {
        const double term = open[f] / freeSurfaceTheta(in.liquidPhi[c], phiNb);
        out.diagonal += term;
        out.surface += term;
        continue;
      }
    }
    out.diagonal += open[f];
  }
  return out;
}

// Cell (i, j, k) anywhere in the grid.
VP_HOST_DEVICE inline CellDiagonal cellDiagonalAt(const PoissonBuildFields& in, int64_t i, int64_t j, int64_t k) {
  const MacLayout& g = in.grid;
  const int64_t c = g.cellIndex(i, j, k);
  const int64_t index[3] = {i, j, k}, step[3] = {1, g.nx, g.nx * g.ny};
  double open[6];
  int64_t neighbour[6];
  for (int a = 0; a < 3; ++a)
    for (int high = 0; high < 2; ++high) {
      int64_t face[3] = {i, j, k};
      face[a] += high;
      const bool atSide = high ? index[a] + 1 == g.cells(a) : index[a] == 0;
      const int f = 2 * a + high;
      open[f] = g.isWall(a, face[a]) ? 0.0 : openedFraction(in.open[a][g.faceIndex(a, face[0], face[1], face[2])]);
      neighbour[f] = atSide ? -1 : high ? c + step[a] : c - step[a];
    }
  return diagonalFromFaces(in, c, open, neighbour);
}

// The same for a cell with a neighbour on both sides along every axis (no domain face).
VP_HOST_DEVICE inline CellDiagonal interiorCellDiagonalAt(const PoissonBuildFields& in, int64_t i, int64_t j,
                                                          int64_t k) {
  const MacLayout& g = in.grid;
  const int64_t c = g.cellIndex(i, j, k), sx = g.nx, sxy = g.nx * g.ny;
  const int64_t fu = g.faceIndex(0, i, j, k), fv = g.faceIndex(1, i, j, k), fw = g.faceIndex(2, i, j, k);
  const double open[6] = {openedFraction(in.open[0][fu]), openedFraction(in.open[0][fu + 1]),
                          openedFraction(in.open[1][fv]), openedFraction(in.open[1][fv + sx]),
                          openedFraction(in.open[2][fw]), openedFraction(in.open[2][fw + sxy])};
  const int64_t neighbour[6] = {c - 1, c + 1, c - sx, c + sx, c - sxy, c + sxy};
  return diagonalFromFaces(in, c, open, neighbour);
}

}  // namespace vp::kernels

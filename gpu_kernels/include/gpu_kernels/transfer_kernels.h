// Kernel bodies of the pressure multigrid's grid transfers (runtime/fluid/pressure/
// multigrid_transfer.h has the mathematics): the renormalized trilinear prolongation of one
// fine cell, and the three one-dimensional gathers of its transpose, the restriction, for one
// coarse value. Functions of an index and plain arrays, for one device thread per value; the
// CPU's row loops (multigrid_transfer.cpp) compute the same values a row at a time, in the same
// order of operations, and are tested bit for bit against these.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

// Which domain sides are Open (Dirichlet), in MacGrid::sides order.
struct TransferSides {
  bool open[6] = {false, false, false, false, false, false};
};

// The two coarse cells fine index i interpolates from along one axis, with their weights. A
// neighbour outside [0, coarseCount) is a ghost: behind a Wall side it is dropped (weight 0, a
// valid index so it can be read); behind an Open side it is the Dirichlet ghost -x_parent, which
// puts the zero at the domain face, so it becomes weight -1/4 on the parent. `presence` is the
// weight the renormalization counts (the ghost is there, only with a mirrored value).
struct AxisStencil {
  int64_t index[2];
  double weight[2];
  double presence[2];
  VP_HOST_DEVICE AxisStencil(int64_t i, int64_t coarseCount, const TransferSides& sides, int axis) {
    const int64_t parent = i >> 1, side = (i & 1) ? parent + 1 : parent - 1;
    index[0] = parent;
    weight[0] = presence[0] = 0.75;
    const bool inside = side >= 0 && side < coarseCount;
    const bool dirichlet = !inside && sides.open[2 * axis + (side < 0 ? 0 : 1)];
    index[1] = inside ? side : parent;
    weight[1] = inside ? 0.25 : dirichlet ? -0.25 : 0.0;
    presence[1] = inside || dirichlet ? 0.25 : 0.0;
  }
};

// The transpose of AxisStencil along one axis: the weights P gives coarse index I at the fine
// indices first .. first + 3 (= 2I - 1 .. 2I + 2), 0 for fine indices outside the grid.
struct AxisWeights {
  int64_t first;
  double weight[4];
  VP_HOST_DEVICE AxisWeights(int64_t I, int64_t fineCount, int64_t coarseCount, const TransferSides& sides,
                             int axis)
      : first(2 * I - 1) {
    for (int x = 0; x < 4; ++x) {
      weight[x] = 0.0;
      const int64_t i = first + x;
      if (i < 0 || i >= fineCount) continue;
      const AxisStencil s(i, coarseCount, sides, axis);
      for (int e = 0; e < 2; ++e)
        if (s.index[e] == I) weight[x] += s.weight[e];
    }
  }
};

// A fine level's and its coarse level's cell counts per axis.
struct TransferDims {
  int64_t nx, ny, nz;  // fine
  int64_t cx, cy, cz;  // coarse
};

// The prolongation's scale at fine cell (i, j, k): 1 / S, S the weight of the fluid (diagonal
// > 0) coarse cells of its stencil (presence weights, ghosts behind Open sides included); 0 on
// a non-fluid fine cell and where no coarse neighbour is fluid.
VP_HOST_DEVICE inline double prolongationScaleAt(const TransferDims& d, const TransferSides& sides,
                                                 const double* fineDiagonal, const double* coarseDiagonal, int64_t i,
                                                 int64_t j, int64_t k) {
  double sum = 0.0;
  if (fineDiagonal[i + d.nx * (j + d.ny * k)] > 0.0) {
    const AxisStencil sx(i, d.cx, sides, 0), sy(j, d.cy, sides, 1), sz(k, d.cz, sides, 2);
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y) {
        const double pyz = sy.presence[y] * sz.presence[z];
        const int64_t base = d.cx * (sy.index[y] + d.cy * sz.index[z]);
        for (int x = 0; x < 2; ++x)
          if (coarseDiagonal[base + sx.index[x]] > 0.0) sum += pyz * sx.presence[x];
      }
  }
  return sum > 0.0 ? 1.0 / sum : 0.0;
}

// fineX += P coarseX at fine cell (i, j, k), where scale (1 / S, multigrid_transfer.h) is not
// 0; the cell keeps its value where it is. T: float or double.
template <class T>
VP_HOST_DEVICE inline void prolongateCell(const TransferDims& d, const TransferSides& sides, int64_t i, int64_t j,
                                          int64_t k, const T* scale, const T* coarseX, T* fineX) {
  const int64_t c = i + d.nx * (j + d.ny * k);
  if (scale[c] == T(0)) return;
  const AxisStencil sx(i, d.cx, sides, 0), sy(j, d.cy, sides, 1), sz(k, d.cz, sides, 2);
  const T wx0 = static_cast<T>(sx.weight[0]), wx1 = static_cast<T>(sx.weight[1]);
  T sum = T(0);
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y) {
      const T* line = coarseX + d.cx * (sy.index[y] + d.cy * sz.index[z]);
      const T wyz = static_cast<T>(sy.weight[y] * sz.weight[z]);
      sum += wyz * (wx0 * line[sx.index[0]] + wx1 * line[sx.index[1]]);
    }
  fineX[c] += scale[c] * sum;
}

// The restriction's gather along x for coarse index I of one fine row: sum over the taps of
// weight * scale * r (taps of weight 0 skipped); scaleRow and rRow are the row's values.
template <class T>
VP_HOST_DEVICE inline T restrictAlongX(const AxisWeights& w, const T* scaleRow, const T* rRow) {
  T sum = T(0);
  for (int x = 0; x < 4; ++x)
    if (w.weight[x] != 0.0) sum += static_cast<T>(w.weight[x]) * scaleRow[w.first + x] * rRow[w.first + x];
  return sum;
}

// The restriction's gather along y or z for one value: sum over the taps t of weight_t *
// in[(first + t) * stride], taps of weight 0 skipped (in: the value at fine index 0 of the
// axis, stride: the distance between neighbours along it).
template <class T>
VP_HOST_DEVICE inline T restrictAlong(const AxisWeights& w, const T* in, int64_t stride) {
  T sum = T(0);
  for (int t = 0; t < 4; ++t)
    if (w.weight[t] != 0.0) sum += static_cast<T>(w.weight[t]) * in[(w.first + t) * stride];
  return sum;
}

}  // namespace vp::kernels

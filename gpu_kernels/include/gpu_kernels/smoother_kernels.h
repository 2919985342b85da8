// Kernel bodies of the pressure multigrid's smoothing and residual (runtime/fluid/pressure/
// multigrid_smoother.h has the method), one cell or one listed boundary cell per call, for one
// device thread each. The CPU's red-black sweep and residual run row loops that compute the
// same values in the same order of operations (tested bit for bit against these); its boundary
// sweeps run boundaryCellUpdate itself.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/poisson_kernels.h"

namespace vp::kernels {

// A cell of a boundary list with its own coefficients, packed in the V-cycle's single
// precision, and the inverse of its diagonal. A face with coupling 0 (closed, or a domain side)
// reads the cell itself, so no neighbour outside the grid is ever read.
struct BoundaryCell {
  int32_t cell;
  float coupling[6];  // faces -x, +x, -y, +y, -z, +z
  float inverseDiagonal;
};

// One Gauss-Seidel update of a listed cell on the boundary sweeps' compact values: `reads` are
// the entry's six places in `values` (runtime's BoundaryCellLists::reads), `rhs` its b.
VP_HOST_DEVICE inline float boundaryCellUpdate(const BoundaryCell& e, const int32_t* reads, const float* values,
                                               float rhs) {
  float sum = 0.0f;
  for (int f = 0; f < 6; ++f) sum += e.coupling[f] * values[reads[f]];
  return (rhs + sum) * e.inverseDiagonal;
}

// Threads of a half-sweep: rows of ceil(nx / 2) (colourCell).
template <class T>
VP_HOST_DEVICE inline int64_t colourThreads(const PoissonStencil<T>& s) {
  return (s.nx + 1) / 2 * s.ny * s.nz;
}

// The cell of colour `colour` ((i + j + k + colour) even) that thread `t` of a half-sweep owns:
// rows of ceil(nx / 2) threads; false when the thread has no cell (the row's odd end).
template <class T>
VP_HOST_DEVICE inline bool colourCell(const PoissonStencil<T>& s, int64_t t, int colour, int64_t* cell) {
  const int64_t half = (s.nx + 1) / 2, row = t / half;
  const int64_t j = row % s.ny, k = row / s.ny;
  const int64_t i = 2 * (t % half) + ((j + k + colour) & 1);
  *cell = i + s.nx * row;
  return i < s.nx;
}

// x_c = (b_c + sum_f A_f x_nb) / A_cc on a fluid cell; other cells are left alone.
template <class T>
VP_HOST_DEVICE inline void gaussSeidelCell(const PoissonStencil<T>& s, int64_t cell, const T* b, T* x) {
  const int64_t i = cell % s.nx, row = cell / s.nx;
  const PoissonRow<T> r(s, row % s.ny, row / s.ny, x);
  if (r.diagonal[i] > T(0)) x[cell] = (b[cell] + r.neighbourSum(i)) / r.diagonal[i];
}

// r_c = b_c - (A x)_c on a fluid cell, 0 on the others.
template <class T>
VP_HOST_DEVICE inline T residualCell(const PoissonStencil<T>& s, int64_t cell, const T* b, const T* x) {
  const int64_t i = cell % s.nx, row = cell / s.nx;
  const PoissonRow<T> r(s, row % s.ny, row / s.ny, x);
  return r.diagonal[i] > T(0) ? b[cell] + r.neighbourSum(i) - r.diagonal[i] * r.x[i] : T(0);
}

}  // namespace vp::kernels

// Kernel bodies of the cut-cell pressure operator's 7-point rows (runtime/fluid/pressure/
// cut_cell_poisson.h) as functions of plain arrays: a level's couplings and diagonal, and one
// grid row (j, k) set up once with its own and its four neighbour rows.
//
// A neighbour row outside the grid is replaced by the row itself: the face coupling there is 0,
// so the product vanishes without a branch. Only the x neighbours of a row's two end cells need
// a bounds test; the interior form has none, so a loop over a row's inner cells vectorizes.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

// Raw arrays and strides of one level (T: double or float). Cell (i, j, k) has index
// i + nx (j + ny k); face arrays are those of a MAC grid (cu: (nx + 1) ny nz, ...).
template <class T>
struct PoissonStencil {
  const T* cu;
  const T* cv;
  const T* cw;
  const T* diagonal;    // 0 on cells that hold no unknown
  const int32_t* span;  // per row [begin, end) of the cells that can hold fluid, or nullptr: all
  int64_t nx, ny, nz, sz;

  VP_HOST_DEVICE int64_t rows() const { return ny * nz; }
  VP_HOST_DEVICE int64_t spanBegin(int64_t row) const { return span ? span[2 * row] : 0; }
  VP_HOST_DEVICE int64_t spanEnd(int64_t row) const { return span ? span[2 * row + 1] : nx; }
};

template <class T>
struct PoissonRow {
  const T* cu;      // cu[i], cu[i + 1]: the cell's -x and +x faces
  const T* cvLow;   // -y faces of the row's cells
  const T* cvHigh;  // +y faces
  const T* cwLow;   // -z faces
  const T* cwHigh;  // +z faces
  const T* diagonal;
  const T* x;
  const T* xDown;   // row j - 1
  const T* xUp;     // row j + 1
  const T* xBack;   // row k - 1
  const T* xFront;  // row k + 1
  int64_t nx;

  // values == nullptr: the coefficients only.
  VP_HOST_DEVICE PoissonRow(const PoissonStencil<T>& s, int64_t j, int64_t k, const T* values) : nx(s.nx) {
    const int64_t row = j + s.ny * k, c0 = s.nx * row;
    cu = s.cu + (s.nx + 1) * row;
    cvLow = s.cv + s.nx * (j + (s.ny + 1) * k);
    cvHigh = cvLow + s.nx;
    cwLow = s.cw + c0;
    cwHigh = cwLow + s.sz;
    diagonal = s.diagonal + c0;
    x = xDown = xUp = xBack = xFront = nullptr;
    if (values == nullptr) return;
    x = values + c0;
    xDown = j > 0 ? x - s.nx : x;
    xUp = j + 1 < s.ny ? x + s.nx : x;
    xBack = k > 0 ? x - s.sz : x;
    xFront = k + 1 < s.nz ? x + s.sz : x;
  }

  // sum_f A_f x_nb over the six faces of cell i, given its x neighbours' values.
  VP_HOST_DEVICE T faceSum(int64_t i, T left, T right) const {
    return cu[i] * left + cu[i + 1] * right + cvLow[i] * xDown[i] + cvHigh[i] * xUp[i] + cwLow[i] * xBack[i] +
           cwHigh[i] * xFront[i];
  }
  // Any cell of the row.
  VP_HOST_DEVICE T neighbourSum(int64_t i) const {
    return faceSum(i, i > 0 ? x[i - 1] : T(0), i + 1 < nx ? x[i + 1] : T(0));
  }
  // A cell with 0 < i < nx - 1: the same value, no branch.
  VP_HOST_DEVICE T interiorNeighbourSum(int64_t i) const { return faceSum(i, x[i - 1], x[i + 1]); }
};

// (L x) at one cell: diagonal x minus the coupled neighbours, 0 on a cell that holds no unknown
// (the CPU's row kernels store the same values a row at a time). For one thread per cell.
template <class T>
VP_HOST_DEVICE inline T poissonApplyCell(const PoissonStencil<T>& s, int64_t cell, const T* x) {
  const int64_t i = cell % s.nx, row = cell / s.nx;
  const PoissonRow<T> r(s, row % s.ny, row / s.ny, x);
  return r.diagonal[i] > T(0) ? r.diagonal[i] * r.x[i] - r.neighbourSum(i) : T(0);
}

}  // namespace vp::kernels

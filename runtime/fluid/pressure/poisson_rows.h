// Row-wise access to a CutCellPoisson's implicit 7-point operator, shared by the CG's operator
// and the multigrid's smoothers and residual. The kernels walk grid rows (j, k) and, inside a
// row, only the span of cells from its first to its last fluid cell: integer divisions per cell
// cost more than the memory traffic, and rows (or row ends) of air above a liquid or inside a
// solid hold no unknowns, so streaming them would only spend bandwidth.
#pragma once

#include <cstdint>

#include "core/parallel_for.h"
#include "fluid/pressure/cut_cell_poisson.h"

namespace vp::poisson_rows {

constexpr int64_t kCellsPerChunk = 4096;

// Raw arrays and strides of a level (T: double or float).
template <class T>
struct Stencil {
  const T* cu;
  const T* cv;
  const T* cw;
  const T* diagonal;
  const int32_t* span;  // PoissonCoefficients::rowSpan, or nullptr: every row spans all its cells
  int64_t nx, ny, nz, sz;

  explicit Stencil(const PoissonCoefficients<T>& op)
      : cu(op.coupling[0].data()), cv(op.coupling[1].data()), cw(op.coupling[2].data()),
        diagonal(op.diagonal.data()), span(op.rowSpan.empty() ? nullptr : op.rowSpan.data()), nx(op.grid.nx),
        ny(op.grid.ny), nz(op.grid.nz), sz(static_cast<int64_t>(op.grid.nx) * op.grid.ny) {}

  int64_t rows() const { return ny * nz; }
  int64_t rowGrain() const { return nx >= kCellsPerChunk ? 1 : kCellsPerChunk / nx; }
  // [begin, end) of the cells of row (j + ny k) that can hold fluid; empty when begin == end.
  int64_t spanBegin(int64_t row) const { return span ? span[2 * row] : 0; }
  int64_t spanEnd(int64_t row) const { return span ? span[2 * row + 1] : nx; }
};

// One grid row (j, k) with its neighbour rows, set up once per row. A neighbour row outside the
// grid is replaced by the row itself: its face coupling is 0, so the product vanishes without a
// branch.
template <class T>
struct Row {
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

  Row(const Stencil<T>& s, int64_t j, int64_t k, const T* values) : nx(s.nx) {
    const int64_t row = j + s.ny * k, c0 = s.nx * row;
    cu = s.cu + (s.nx + 1) * row;
    cvLow = s.cv + s.nx * (j + (s.ny + 1) * k);
    cvHigh = cvLow + s.nx;
    cwLow = s.cw + c0;
    cwHigh = cwLow + s.sz;
    diagonal = s.diagonal + c0;
    x = xDown = xUp = xBack = xFront = nullptr;  // values == nullptr: coefficients only
    if (values == nullptr) return;
    x = values + c0;
    xDown = j > 0 ? x - s.nx : x;
    xUp = j + 1 < s.ny ? x + s.nx : x;
    xBack = k > 0 ? x - s.sz : x;
    xFront = k + 1 < s.nz ? x + s.sz : x;
  }

  // sum_f A_f x_nb over the six faces of cell i of the row.
  T neighbourSum(int64_t i) const {
    const T left = i > 0 ? x[i - 1] : T(0);
    const T right = i + 1 < nx ? x[i + 1] : T(0);
    return cu[i] * left + cu[i + 1] * right + cvLow[i] * xDown[i] + cvHigh[i] * xUp[i] + cwLow[i] * xBack[i] +
           cwHigh[i] * xFront[i];
  }
};

// Calls body(j, k, index of the row's first cell) for every row in parallel.
template <class T, class Body>
void forEachRow(TaskSystem& tasks, const Stencil<T>& s, const Body& body) {
  parallelFor(tasks, s.rows(), s.rowGrain(), [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) body(row % s.ny, row / s.ny, s.nx * row);
  });
}

// Writes 0 to the values of row `row` (rowValues: its first cell) outside its span.
template <class T, class V>
void clearOutsideSpan(const Stencil<T>& s, int64_t row, V* rowValues) {
  for (int64_t i = 0, e = s.spanBegin(row); i < e; ++i) rowValues[i] = V(0);
  for (int64_t i = s.spanEnd(row); i < s.nx; ++i) rowValues[i] = V(0);
}

}  // namespace vp::poisson_rows

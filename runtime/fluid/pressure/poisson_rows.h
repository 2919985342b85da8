// Row-wise access to a CutCellPoisson's implicit 7-point operator, shared by the CG's operator
// and the multigrid's smoothers and residual. The kernels walk grid rows (j, k) and, inside a
// row, only the span of cells from its first to its last fluid cell: integer divisions per cell
// cost more than the memory traffic, and rows (or row ends) of air above a liquid or inside a
// solid hold no unknowns, so streaming them would only spend bandwidth.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/isa_clones.h"
#include "core/parallel_for.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "gpu_kernels/poisson_kernels.h"

namespace vp::poisson_rows {

constexpr int64_t kCellsPerChunk = 4096;

// A level's raw arrays (gpu_kernels/poisson_kernels.h), taken from its coefficients.
template <class T>
struct Stencil : kernels::PoissonStencil<T> {
  explicit Stencil(const PoissonCoefficients<T>& op)
      : kernels::PoissonStencil<T>{op.coupling[0].data(),
                                   op.coupling[1].data(),
                                   op.coupling[2].data(),
                                   op.diagonal.data(),
                                   op.rowSpan.empty() ? nullptr : op.rowSpan.data(),
                                   op.grid.nx,
                                   op.grid.ny,
                                   op.grid.nz,
                                   static_cast<int64_t>(op.grid.nx) * op.grid.ny} {}

  int64_t rowGrain() const { return this->nx >= kCellsPerChunk ? 1 : kCellsPerChunk / this->nx; }
};

template <class T>
using Row = kernels::PoissonRow<T>;

// Calls body(m, i, row.neighbourSum(i)) for the cells i = first + kStep m, m in [0, count), in
// order: cells at the row's ends through the bounds-tested sum, the others through the
// branch-free one, so a body without branches of its own vectorizes.
template <int64_t kStep, class T, class Body>
VP_CLONE_INLINE inline void forEachNeighbourSum(const Row<T>& row, int64_t first, int64_t count, const Body& body) {
  // Interior cells: 1 <= first + kStep m <= nx - 2.
  const int64_t innerBegin = std::min(count, first >= 1 ? int64_t(0) : (1 - first + kStep - 1) / kStep);
  const int64_t lastInner = row.nx - 2 - first;
  const int64_t innerEnd = std::max(innerBegin, std::min(count, lastInner >= 0 ? lastInner / kStep + 1 : 0));
  for (int64_t m = 0; m < innerBegin; ++m) body(m, first + kStep * m, row.neighbourSum(first + kStep * m));
  for (int64_t m = innerBegin; m < innerEnd; ++m)
    body(m, first + kStep * m, row.interiorNeighbourSum(first + kStep * m));
  for (int64_t m = innerEnd; m < count; ++m) body(m, first + kStep * m, row.neighbourSum(first + kStep * m));
}

// Row kernels (poisson_rows.cpp), each over the cells of row (j, k) of a level. Each computes
// its values over chunks of the row's span (a sweep: its colour's cells only) into a local
// buffer, in a loop without branches, then stores them: the operator's value on the fluid cells
// (diagonal > 0), 0 on the others (a Continue sweep stores their old value back). Written so
// that both loops vectorize; GCC 12 does so in the VP_ISA_CLONES builds (the stores' selects
// need AVX2 or better; the baseline clone vectorizes the first loop only).

// out = A x: the CG's operator.
void applyRow(const Stencil<double>& s, int64_t j, int64_t k, const double* x, double* out);

// r = b - A x: the multigrid's residual, row (j, k) of it into rowResidual (nx values), so that
// the restriction can take it a row at a time without storing the whole residual.
void residualRow(const Stencil<float>& s, int64_t j, int64_t k, const float* b, const float* x, float* rowResidual);
void residualRow(const Stencil<double>& s, int64_t j, int64_t k, const double* b, const double* x,
                 double* rowResidual);

// out = in + w D^-1 (b - A in): a damped Jacobi sweep's row (in == nullptr: from in = 0, so
// out = w D^-1 b); out must not alias in.
void jacobiRow(const Stencil<float>& s, int64_t j, int64_t k, const float* b, const float* in, float* out,
               float weight);
void jacobiRow(const Stencil<double>& s, int64_t j, int64_t k, const double* b, const double* in, double* out,
               double weight);

// How a Gauss-Seidel half-sweep of a row treats x. Continue: x is the current iterate, and the
// non-fluid cells keep their value (0; it is stored back). The two FromZero kinds make a sweep
// that starts from x = 0 without x having been cleared: the first colour ignores its neighbours
// (they are 0) and clears the row outside its span; both colours write every cell of theirs,
// non-fluid ones 0.
enum class SweepStart { Continue, FromZeroFirstColour, FromZeroSecondColour };

// x_i = (b_i + sum_f A_f x_nb) / A_ii on the fluid cells of one colour, (i + j + k + colour)
// even; the other colour's cells are not written.
void gaussSeidelRow(const Stencil<float>& s, int64_t j, int64_t k, const float* b, float* x, int colour,
                    SweepStart start);
void gaussSeidelRow(const Stencil<double>& s, int64_t j, int64_t k, const double* b, double* x, int colour,
                    SweepStart start);

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

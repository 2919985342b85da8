// Row kernels of the cut-cell pressure operator (see poisson_rows.h).
#include "fluid/pressure/poisson_rows.h"

#include <limits>

#include "core/isa_clones.h"

namespace vp::poisson_rows {
namespace {

// Cells per chunk of a row: the chunk's values live in a buffer on the stack.
constexpr int64_t kRowChunk = 256;

// The kernels divide by the diagonal in cells where it is 0 (non-fluid cells inside a span) and
// drop the inf or NaN in the store's select: IEEE 754 arithmetic (no trapping floating-point
// exceptions enabled), which the runtime assumes throughout.
static_assert(std::numeric_limits<double>::is_iec559 && std::numeric_limits<float>::is_iec559,
              "IEEE 754 floating point");

// For the row's span cells first, first + kStep, ... in chunks: compute(first, count, values)
// fills values[m] for the chunk's cells first + kStep m, then store(i, values[m]) for each.
template <int64_t kStep, class T, class Compute, class Store>
VP_CLONE_INLINE inline void forSpanInChunks(int64_t first, int64_t end, const Compute& compute, const Store& store) {
  T values[kRowChunk];
  for (int64_t begin = first; begin < end; begin += kStep * kRowChunk) {
    const int64_t count = std::min(kRowChunk, (end - begin + kStep - 1) / kStep);
    compute(begin, count, values);
    for (int64_t m = 0; m < count; ++m) store(begin + kStep * m, values[m]);
  }
}

// A chunk's computation for forSpanInChunks: values[m] = value(i, the neighbour sum of cell i)
// for its cells i = first + kStep m.
template <int64_t kStep, class T, class Value>
VP_CLONE_INLINE inline auto fromNeighbourSums(const Row<T>& r, const Value& value) {
  return [&r, value](int64_t first, int64_t count, T* values) VP_CLONE_INLINE {
    forEachNeighbourSum<kStep>(r, first, count,
                               [&](int64_t m, int64_t i, T sum) VP_CLONE_INLINE { values[m] = value(i, sum); });
  };
}

// Row `row`'s values o (its first cell): compute's values on its fluid cells, 0 on its other
// cells (outside its span too).
template <class T, class Compute>
VP_CLONE_INLINE inline void storeFluidRow(const Stencil<T>& s, const Row<T>& r, int64_t row, T* o,
                                          const Compute& compute) {
  clearOutsideSpan(s, row, o);
  forSpanInChunks<1, T>(s.spanBegin(row), s.spanEnd(row), compute,
                        [&](int64_t i, T value) VP_CLONE_INLINE { o[i] = r.diagonal[i] > T(0) ? value : T(0); });
}

template <class T>
VP_CLONE_INLINE inline void applyRowBody(const Stencil<T>& s, int64_t j, int64_t k, const T* x, T* out) {
  const Row<T> r(s, j, k, x);
  const int64_t row = j + s.ny * k;
  storeFluidRow(s, r, row, out + s.nx * row, fromNeighbourSums<1>(r, [&r](int64_t i, T sum) VP_CLONE_INLINE {
                  return r.diagonal[i] * r.x[i] - sum;
                }));
}

template <class T>
VP_CLONE_INLINE inline void residualRowBody(const Stencil<T>& s, int64_t j, int64_t k, const T* b, const T* x,
                                            T* rowResidual) {
  const Row<T> r(s, j, k, x);
  const int64_t row = j + s.ny * k;
  const T* br = b + s.nx * row;
  storeFluidRow(s, r, row, rowResidual, fromNeighbourSums<1>(r, [&r, br](int64_t i, T sum) VP_CLONE_INLINE {
                  return br[i] + sum - r.diagonal[i] * r.x[i];
                }));
}

template <class T>
VP_CLONE_INLINE inline void jacobiRowBody(const Stencil<T>& s, int64_t j, int64_t k, const T* b, const T* in, T* out,
                                          T weight) {
  const Row<T> r(s, j, k, in);
  const int64_t row = j + s.ny * k;
  const T* br = b + s.nx * row;
  if (in == nullptr) {
    storeFluidRow(s, r, row, out + s.nx * row, [&](int64_t first, int64_t count, T* values) VP_CLONE_INLINE {
      for (int64_t m = 0; m < count; ++m) values[m] = weight * br[first + m] / r.diagonal[first + m];
    });
    return;
  }
  T* rowOut = out + s.nx * row;
  storeFluidRow(s, r, row, rowOut, fromNeighbourSums<1>(r, [&r, br, weight](int64_t i, T sum) VP_CLONE_INLINE {
                  return r.x[i] + weight * (br[i] + sum - r.diagonal[i] * r.x[i]) / r.diagonal[i];
                }));
}

// Only the colour's cells are computed and stored (every second cell); what they read is the
// other colour, which the fused sweep's schedule (multigrid_smoother.cpp) never writes while
// this half-sweep runs. Computing every cell and dropping half would read cells that another
// slab may be writing at that moment.
template <class T>
VP_CLONE_INLINE inline void gaussSeidelRowBody(const Stencil<T>& s, int64_t j, int64_t k, const T* b, T* x,
                                               int colour, SweepStart start) {
  const Row<T> r(s, j, k, x);
  const int64_t row = j + s.ny * k, c0 = s.nx * row;
  const T* br = b + c0;
  T* xr = x + c0;
  const int64_t begin = s.spanBegin(row), end = s.spanEnd(row);
  const int64_t first = begin + ((begin + j + k + colour) & 1);
  if (start == SweepStart::FromZeroFirstColour) clearOutsideSpan(s, row, xr);
  const auto fromNeighbours = fromNeighbourSums<2>(
      r, [&r, br](int64_t i, T sum) VP_CLONE_INLINE { return (br[i] + sum) / r.diagonal[i]; });
  auto alone = [&](int64_t from, int64_t count, T* values) VP_CLONE_INLINE {
    for (int64_t m = 0; m < count; ++m) values[m] = (br[from + 2 * m] + T(0)) / r.diagonal[from + 2 * m];
  };
  auto keepNonFluid = [&](int64_t i, T value) VP_CLONE_INLINE { xr[i] = r.diagonal[i] > T(0) ? value : xr[i]; };
  auto clearNonFluid = [&](int64_t i, T value) VP_CLONE_INLINE { xr[i] = r.diagonal[i] > T(0) ? value : T(0); };
  switch (start) {
    case SweepStart::Continue: forSpanInChunks<2, T>(first, end, fromNeighbours, keepNonFluid); break;
    case SweepStart::FromZeroFirstColour: forSpanInChunks<2, T>(first, end, alone, clearNonFluid); break;
    case SweepStart::FromZeroSecondColour: forSpanInChunks<2, T>(first, end, fromNeighbours, clearNonFluid); break;
  }
}

}  // namespace

VP_ISA_CLONES
void applyRow(const Stencil<double>& s, int64_t j, int64_t k, const double* x, double* out) {
  applyRowBody(s, j, k, x, out);
}

VP_ISA_CLONES
void residualRow(const Stencil<float>& s, int64_t j, int64_t k, const float* b, const float* x, float* rowResidual) {
  residualRowBody(s, j, k, b, x, rowResidual);
}

VP_ISA_CLONES
void residualRow(const Stencil<double>& s, int64_t j, int64_t k, const double* b, const double* x,
                 double* rowResidual) {
  residualRowBody(s, j, k, b, x, rowResidual);
}

VP_ISA_CLONES
void jacobiRow(const Stencil<float>& s, int64_t j, int64_t k, const float* b, const float* in, float* out,
               float weight) {
  jacobiRowBody(s, j, k, b, in, out, weight);
}

VP_ISA_CLONES
void jacobiRow(const Stencil<double>& s, int64_t j, int64_t k, const double* b, const double* in, double* out,
               double weight) {
  jacobiRowBody(s, j, k, b, in, out, weight);
}

VP_ISA_CLONES
void gaussSeidelRow(const Stencil<float>& s, int64_t j, int64_t k, const float* b, float* x, int colour,
                    SweepStart start) {
  gaussSeidelRowBody(s, j, k, b, x, colour, start);
}

VP_ISA_CLONES
void gaussSeidelRow(const Stencil<double>& s, int64_t j, int64_t k, const double* b, double* x, int colour,
                    SweepStart start) {
  gaussSeidelRowBody(s, j, k, b, x, colour, start);
}

}  // namespace vp::poisson_rows

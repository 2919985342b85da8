// Renormalized trilinear prolongation and its transpose (see multigrid_transfer.h).
#include "fluid/pressure/multigrid_transfer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "core/isa_clones.h"
#include "core/parallel_for.h"
#include "fluid/pressure/poisson_rows.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 16;
// Fine rows up to this long take their residual in a buffer on the stack.
constexpr int64_t kStackRow = 1024;

using kernels::AxisStencil;
using kernels::AxisWeights;

// out[I] = kernels::restrictAlong for each of `count` values of a row, a tap at a time over
// the whole row (the same operations per value, in the same order; the loop over I
// vectorizes): one pass of the separable restriction along y or z (in: the row at fine index
// 0 of the axis).
template <class T>
void gatherRows(const AxisWeights& w, int64_t count, const T* in, int64_t stride, T* out) {
  for (int64_t I = 0; I < count; ++I) out[I] = T(0);
  for (int t = 0; t < 4; ++t) {
    if (w.weight[t] == 0.0) continue;
    const T weight = static_cast<T>(w.weight[t]);
    const T* line = in + (w.first + t) * stride;
    for (int64_t I = 0; I < count; ++I) out[I] += weight * line[I];
  }
}

// AxisStencil along x for every fine i of a row, as arrays, so a row's loop has no branches.
template <class T>
struct XStencils {
  Array<int32_t> index[2];
  Array<T> weight[2];
  int64_t coarseCount;
  XStencils(int64_t nx, int64_t cx, const TransferSides& sides) : coarseCount(cx) {
    for (int e = 0; e < 2; ++e) index[e].resize(static_cast<size_t>(nx)), weight[e].resize(static_cast<size_t>(nx));
    for (int64_t i = 0; i < nx; ++i) {
      const AxisStencil s(i, cx, sides, 0);
      for (int e = 0; e < 2; ++e) {
        index[e][static_cast<size_t>(i)] = static_cast<int32_t>(s.index[e]);
        weight[e][static_cast<size_t>(i)] = static_cast<T>(s.weight[e]);
      }
    }
  }
};

// One fine row of fineX += P coarseX: the four coarse lines (y, z neighbours) it reads, with
// their y-z weights.
template <class T>
struct ProlongationRow {
  const T* lines[4];
  T wyz[4];
  const XStencils<T>* x;
  const T* scale;  // the row's
  T* fineX;        // the row's
};

// kernels::prolongateCell for the cells of one row, in the same order of operations: a fine
// cell 2I or 2I + 1 with both its coarse neighbours inside takes I and I - 1 or I + 1:
// those cells go in pairs per coarse I, their values into a buffer (contiguous coarse loads, no
// branch), then stored where the cell's scale is not 0 (a cell of scale 0, non-fluid or without
// a fluid coarse neighbour, keeps its value). The few cells at the row's ends go one by one
// through the stencil arrays.
template <class T>
VP_CLONE_INLINE inline void prolongateRowBody(const ProlongationRow<T>& r) {
  constexpr int64_t kPairs = 128;
  T updated[2 * kPairs];
  const XStencils<T>& xs = *r.x;
  const int64_t nx = static_cast<int64_t>(xs.index[0].size()), cx = xs.coarseCount;
  const T *w0 = xs.weight[0].data(), *w1 = xs.weight[1].data();
  const T *l0 = r.lines[0], *l1 = r.lines[1], *l2 = r.lines[2], *l3 = r.lines[3];
  const T a0 = r.wyz[0], a1 = r.wyz[1], a2 = r.wyz[2], a3 = r.wyz[3];
  const T* scale = r.scale;
  T* fineX = r.fineX;
  auto single = [&](int64_t i) VP_CLONE_INLINE {
    if (scale[i] == T(0)) return;
    const int32_t p = xs.index[0][static_cast<size_t>(i)], q = xs.index[1][static_cast<size_t>(i)];
    T sum = T(0);
    sum += a0 * (w0[i] * l0[p] + w1[i] * l0[q]);
    sum += a1 * (w0[i] * l1[p] + w1[i] * l1[q]);
    sum += a2 * (w0[i] * l2[p] + w1[i] * l2[q]);
    sum += a3 * (w0[i] * l3[p] + w1[i] * l3[q]);
    fineX[i] += scale[i] * sum;
  };
  const int64_t pairBegin = std::min<int64_t>(1, cx);
  const int64_t pairEnd = std::max(pairBegin, std::min(cx - 1, nx >= 2 ? (nx - 2) / 2 + 1 : 0));
  for (int64_t i = 0; i < 2 * pairBegin && i < nx; ++i) single(i);
  for (int64_t from = pairBegin; from < pairEnd; from += kPairs) {
    const int64_t to = std::min(pairEnd, from + kPairs);
    for (int64_t I = from; I < to; ++I) {
      const int64_t e = 2 * I, o = e + 1;
      T even = T(0), odd = T(0);
      even += a0 * (w0[e] * l0[I] + w1[e] * l0[I - 1]);
      even += a1 * (w0[e] * l1[I] + w1[e] * l1[I - 1]);
      even += a2 * (w0[e] * l2[I] + w1[e] * l2[I - 1]);
      even += a3 * (w0[e] * l3[I] + w1[e] * l3[I - 1]);
      odd += a0 * (w0[o] * l0[I] + w1[o] * l0[I + 1]);
      odd += a1 * (w0[o] * l1[I] + w1[o] * l1[I + 1]);
      odd += a2 * (w0[o] * l2[I] + w1[o] * l2[I + 1]);
      odd += a3 * (w0[o] * l3[I] + w1[o] * l3[I + 1]);
      updated[e - 2 * from] = fineX[e] + scale[e] * even;
      updated[o - 2 * from] = fineX[o] + scale[o] * odd;
    }
    for (int64_t i = 2 * from; i < 2 * to; ++i) fineX[i] = scale[i] != T(0) ? updated[i - 2 * from] : fineX[i];
  }
  for (int64_t i = std::max(2 * pairEnd, 2 * pairBegin); i < nx; ++i) single(i);
}

VP_ISA_CLONES
void prolongateRow(const ProlongationRow<float>& r) { prolongateRowBody(r); }

VP_ISA_CLONES
void prolongateRow(const ProlongationRow<double>& r) { prolongateRowBody(r); }

// AxisWeights along x for every coarse I, with their weights also as arrays (weight[t][I]) for
// the coarse cells whose four fine cells 2I - 1 .. 2I + 2 all lie in the row.
template <class T>
struct XWeights {
  Array<AxisWeights> all;
  Array<T> weight[4];
  int64_t innerBegin, innerEnd;  // those coarse cells
  XWeights(Array<AxisWeights> perCell, int64_t nx) : all(std::move(perCell)) {
    const int64_t cx = static_cast<int64_t>(all.size());
    innerBegin = std::min<int64_t>(1, cx);
    innerEnd = std::max(innerBegin, std::min(cx, nx >= 3 ? (nx - 3) / 2 + 1 : 0));
    for (int t = 0; t < 4; ++t) {
      weight[t].resize(all.size());
      for (size_t I = 0; I < all.size(); ++I) weight[t][I] = static_cast<T>(all[I].weight[t]);
    }
  }
};

// One fine row's x gather of the restriction: out[I] = sum_t w_t(I) scale r at 2I - 1 + t. The
// cells at the row's ends skip taps outside it (and taps of weight 0); the others take all four
// without a branch (their weights are the interior ones, none 0).
template <class T>
VP_CLONE_INLINE inline void restrictRowAlongXBody(const XWeights<T>& xw, const T* scale, const T* r, T* out) {
  const int64_t cx = static_cast<int64_t>(xw.all.size());
  auto atEnd = [&](int64_t I) VP_CLONE_INLINE {
    out[I] = kernels::restrictAlongX(xw.all[static_cast<size_t>(I)], scale, r);
  };
  for (int64_t I = 0; I < xw.innerBegin; ++I) atEnd(I);
  const T *w0 = xw.weight[0].data(), *w1 = xw.weight[1].data(), *w2 = xw.weight[2].data(), *w3 = xw.weight[3].data();
  for (int64_t I = xw.innerBegin; I < xw.innerEnd; ++I) {
    const int64_t f = 2 * I - 1;
    T sum = T(0);
    sum += w0[I] * scale[f] * r[f];
    sum += w1[I] * scale[f + 1] * r[f + 1];
    sum += w2[I] * scale[f + 2] * r[f + 2];
    sum += w3[I] * scale[f + 3] * r[f + 3];
    out[I] = sum;
  }
  for (int64_t I = xw.innerEnd; I < cx; ++I) atEnd(I);
}

VP_ISA_CLONES
void restrictRowAlongX(const XWeights<float>& xw, const float* scale, const float* r, float* out) {
  restrictRowAlongXBody(xw, scale, r, out);
}

VP_ISA_CLONES
void restrictRowAlongX(const XWeights<double>& xw, const double* scale, const double* r, double* out) {
  restrictRowAlongXBody(xw, scale, r, out);
}

}  // namespace

void computeProlongationScale(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                              const TransferSides& sides, Array<double>* scale) {
  SlabPasses passes(tasks);
  appendComputeProlongationScale(fine, coarse, sides, scale, &passes);
  passes.runAll();
}

void prolongationScaleRow(const CutCellPoisson& fine, const CutCellPoisson& coarse, const TransferSides& sides,
                          int64_t row, double* scale) {
  const kernels::TransferDims d{fine.grid.nx, fine.grid.ny, fine.grid.nz, coarse.grid.nx, coarse.grid.ny,
                                coarse.grid.nz};
  const int64_t j = row % d.ny, k = row / d.ny;
  for (int64_t i = 0; i < d.nx; ++i)
    scale[i] = kernels::prolongationScaleAt(d, sides, fine.diagonal.data(), coarse.diagonal.data(), i, j, k);
}

void appendComputeProlongationScale(const CutCellPoisson& fine, const CutCellPoisson& coarse,
                                    const TransferSides& sides, Array<double>* scale, SlabPasses* passes) {
  const CutCellPoisson* fp = &fine;
  const CutCellPoisson* cp = &coarse;
  passes->addStep([fp, cp, sides, scale, passes] {
    const int64_t nx = fp->grid.nx, rows = static_cast<int64_t>(fp->grid.ny) * fp->grid.nz;
    scale->resize(static_cast<size_t>(nx * rows));
    passes->addParallel(rows, nx, kRowGrain, [=](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) prolongationScaleRow(*fp, *cp, sides, row, scale->data() + nx * row);
    });
  });
}

template <class T>
void prolongateAdd(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                   const TransferSides& sides, const T* scale, const T* coarseX, T* fineX) {
  const int64_t nx = fine.grid.nx, ny = fine.grid.ny, nz = fine.grid.nz;
  const int64_t cx = coarse.grid.nx, cy = coarse.grid.ny, cz = coarse.grid.nz;
  const XStencils<T> xs(nx, cx, sides);
  parallelFor(tasks, ny * nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t j = row % ny, k = row / ny;
      const AxisStencil sy(j, cy, sides, 1), sz(k, cz, sides, 2);
      ProlongationRow<T> r;
      for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y) {
          r.lines[2 * z + y] = coarseX + cx * (sy.index[y] + cy * sz.index[z]);
          r.wyz[2 * z + y] = static_cast<T>(sy.weight[y] * sz.weight[z]);
        }
      r.x = &xs;
      r.scale = scale + nx * row;
      r.fineX = fineX + nx * row;
      prolongateRow(r);
    }
  });
}

template <class T>
void restrictResidual(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                      const TransferSides& sides, const T* scale, const LevelResidual<T>& residual, T* coarseB,
                      Array<T>* scratch) {
  const int64_t nx = fine.grid.nx, ny = fine.grid.ny, nz = fine.grid.nz;
  const int64_t cx = coarse.grid.nx, cy = coarse.grid.ny, cz = coarse.grid.nz;
  // R is P^T with P's weights a product over the axes, so it runs as three 1D gathers (x, then
  // y, then z), each coarse value collecting the fine indices 2I-1 .. 2I+2 whose stencils name
  // it with the weight their AxisStencil gives it (AxisWeights): 4 + 4 + 4 multiply-adds per
  // coarse value of each pass instead of 64.
  Array<AxisWeights> wx, wy, wz;
  for (int64_t I = 0; I < cx; ++I) wx.emplace_back(I, nx, cx, sides, 0);
  for (int64_t J = 0; J < cy; ++J) wy.emplace_back(J, ny, cy, sides, 1);
  for (int64_t K = 0; K < cz; ++K) wz.emplace_back(K, nz, cz, sides, 2);
  scratch->resize(static_cast<size_t>(cx * ny * nz + cx * cy * nz));
  T* alongX = scratch->data();           // cx * ny * nz
  T* alongY = alongX + cx * ny * nz;     // cx * cy * nz
  const XWeights<T> xw(std::move(wx), nx);
  const poisson_rows::Stencil<T> stencil(*residual.op);
  parallelFor(tasks, ny * nz, kRowGrain, [&](int64_t begin, int64_t end) {
    T onStack[kStackRow];
    Array<T> onHeap;
    if (nx > kStackRow) onHeap.resize(static_cast<size_t>(nx));
    T* r = nx > kStackRow ? onHeap.data() : onStack;
    for (int64_t row = begin; row < end; ++row) {
      poisson_rows::residualRow(stencil, row % ny, row / ny, residual.b, residual.x, r);
      restrictRowAlongX(xw, scale + nx * row, r, alongX + cx * row);
    }
  });
  parallelFor(tasks, cy * nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t J = row % cy, k = row / cy;
      gatherRows(wy[static_cast<size_t>(J)], cx, alongX + cx * ny * k, cx, alongY + cx * row);
    }
  });
  parallelFor(tasks, cy * cz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t J = row % cy, K = row / cy;
      T* out = coarseB + cx * row;
      gatherRows(wz[static_cast<size_t>(K)], cx, alongY + cx * J, cx * cy, out);
      const double* diagonal = coarse.diagonal.data() + cx * row;
      for (int64_t I = 0; I < cx; ++I)
        if (!(diagonal[I] > 0.0)) out[I] = T(0);
    }
  });
}

#define VP_INSTANTIATE_TRANSFERS(T)                                                                        \
  template void prolongateAdd<T>(TaskSystem&, const CutCellPoisson&, const CutCellPoisson&, const TransferSides&, \
                                 const T*, const T*, T*);                                                      \
  template void restrictResidual<T>(TaskSystem&, const CutCellPoisson&, const CutCellPoisson&,                   \
                                    const TransferSides&, const T*, const LevelResidual<T>&, T*, Array<T>*);
VP_INSTANTIATE_TRANSFERS(double)
VP_INSTANTIATE_TRANSFERS(float)
#undef VP_INSTANTIATE_TRANSFERS

}  // namespace vp

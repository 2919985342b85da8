// Renormalized trilinear prolongation and its transpose (see multigrid_transfer.h).
#include "fluid/multigrid_transfer.h"

#include "core/parallel_for.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 16;

// The two coarse cells fine index i interpolates from along one axis, with their weights; a
// neighbour outside [0, coarseCount) gets weight 0 (and a valid index, so it can be read).
struct AxisStencil {
  int64_t index[2];
  double weight[2];
  AxisStencil(int64_t i, int64_t coarseCount) {
    const int64_t parent = i >> 1, side = (i & 1) ? parent + 1 : parent - 1;
    index[0] = parent;
    weight[0] = 0.75;
    const bool inside = side >= 0 && side < coarseCount;
    index[1] = inside ? side : parent;
    weight[1] = inside ? 0.25 : 0.0;
  }
};

// Calls body(fine cell, coarse index, weight) for the 8 stencil entries of every fluid fine
// cell, in parallel over fine rows.
template <class Body>
void forEachFineStencil(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                        const Body& body) {
  const int64_t nx = fine.grid.nx, ny = fine.grid.ny, nz = fine.grid.nz;
  const int64_t cx = coarse.grid.nx, cy = coarse.grid.ny, cz = coarse.grid.nz;
  parallelFor(tasks, ny * nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t j = row % ny, k = row / ny;
      const AxisStencil sy(j, cy), sz(k, cz);
      for (int64_t i = 0; i < nx; ++i) {
        const int64_t c = i + nx * row;
        if (!(fine.diagonal[static_cast<size_t>(c)] > 0.0)) continue;
        const AxisStencil sx(i, cx);
        for (int z = 0; z < 2; ++z)
          for (int y = 0; y < 2; ++y) {
            const double wyz = sy.weight[y] * sz.weight[z];
            const int64_t base = cx * (sy.index[y] + cy * sz.index[z]);
            body(c, base + sx.index[0], wyz * sx.weight[0]);
            body(c, base + sx.index[1], wyz * sx.weight[1]);
          }
      }
    }
  });
}

}  // namespace

void computeProlongationScale(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                              std::vector<double>* scale) {
  const int64_t cells = static_cast<int64_t>(fine.diagonal.size());
  std::vector<double>& s = *scale;
  s.assign(static_cast<size_t>(cells), 0.0);
  forEachFineStencil(tasks, fine, coarse, [&](int64_t c, int64_t coarseCell, double w) {
    if (coarse.diagonal[static_cast<size_t>(coarseCell)] > 0.0) s[static_cast<size_t>(c)] += w;
  });
  parallelFor(tasks, cells, 4096, [&](int64_t begin, int64_t end) {
    for (int64_t c = begin; c < end; ++c) s[static_cast<size_t>(c)] = s[c] > 0.0 ? 1.0 / s[c] : 0.0;
  });
}

void prolongateAdd(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                   const double* scale, const double* coarseX, double* fineX) {
  const int64_t nx = fine.grid.nx, ny = fine.grid.ny, nz = fine.grid.nz;
  const int64_t cx = coarse.grid.nx, cy = coarse.grid.ny, cz = coarse.grid.nz;
  // Written out rather than through forEachFineStencil: the sum stays in a register.
  parallelFor(tasks, ny * nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t j = row % ny, k = row / ny;
      const AxisStencil sy(j, cy), sz(k, cz);
      const double* lines[4];
      double wyz[4];
      for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y) {
          lines[2 * z + y] = coarseX + cx * (sy.index[y] + cy * sz.index[z]);
          wyz[2 * z + y] = sy.weight[y] * sz.weight[z];
        }
      for (int64_t i = 0; i < nx; ++i) {
        const int64_t c = i + nx * row;
        const double s = scale[c];
        if (s == 0.0) continue;
        const AxisStencil sx(i, cx);
        double sum = 0.0;
        for (int l = 0; l < 4; ++l)
          sum += wyz[l] * (sx.weight[0] * lines[l][sx.index[0]] + sx.weight[1] * lines[l][sx.index[1]]);
        fineX[c] += s * sum;
      }
    }
  });
}

void restrictResidual(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                      const double* scale, const double* fineR, double* coarseB) {
  const int64_t nx = fine.grid.nx, ny = fine.grid.ny, nz = fine.grid.nz;
  const int64_t cx = coarse.grid.nx, cy = coarse.grid.ny, cz = coarse.grid.nz;
  // Gather: coarse cell I collects fine 2I-1 .. 2I+2 per axis (weights 1/4, 3/4, 3/4, 1/4), the
  // fine cells whose stencils name I (see AxisStencil), so every coarse value is written once.
  constexpr double kWeight[4] = {0.25, 0.75, 0.75, 0.25};
  parallelFor(tasks, cy * cz, 4, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t J = row % cy, K = row / cy;
      for (int64_t I = 0; I < cx; ++I) {
        const int64_t C = I + cx * row;
        if (!(coarse.diagonal[static_cast<size_t>(C)] > 0.0)) {
          coarseB[C] = 0.0;
          continue;
        }
        double sum = 0.0;
        for (int z = 0; z < 4; ++z) {
          const int64_t k = 2 * K - 1 + z;
          if (k < 0 || k >= nz) continue;
          for (int y = 0; y < 4; ++y) {
            const int64_t j = 2 * J - 1 + y;
            if (j < 0 || j >= ny) continue;
            const double wyz = kWeight[z] * kWeight[y];
            const int64_t base = nx * (j + ny * k);
            for (int x = 0; x < 4; ++x) {
              const int64_t i = 2 * I - 1 + x;
              if (i < 0 || i >= nx) continue;
              sum += wyz * kWeight[x] * scale[base + i] * fineR[base + i];
            }
          }
        }
        coarseB[C] = sum;
      }
    }
  });
}

}  // namespace vp

// Red-black Gauss-Seidel, damped Jacobi and the residual of a multigrid level (see
// multigrid_smoother.h).
#include "fluid/multigrid_smoother.h"

#include "core/parallel_for.h"

namespace vp {
namespace {

constexpr int64_t kCellsPerChunk = 4096;

// Raw arrays and strides of a level, and the neighbour sum sum_f A_f x_nb of one cell.
struct Stencil {
  const double* cu;
  const double* cv;
  const double* cw;
  const double* diagonal;
  int64_t nx, ny, nz, sz;

  explicit Stencil(const CutCellPoisson& op)
      : cu(op.coupling[0].data()), cv(op.coupling[1].data()), cw(op.coupling[2].data()),
        diagonal(op.diagonal.data()), nx(op.grid.nx), ny(op.grid.ny), nz(op.grid.nz),
        sz(static_cast<int64_t>(op.grid.nx) * op.grid.ny) {}

  int64_t rows() const { return ny * nz; }
  int64_t rowGrain() const { return nx >= kCellsPerChunk ? 1 : kCellsPerChunk / nx; }

  // Boundary faces have coupling 0, so a neighbour index is only read when it exists.
  double neighbourSum(int64_t row, int64_t i, const double* x) const {
    const int64_t j = row % ny, k = row / ny;
    const int64_t c = i + nx * row;
    const int64_t fu = i + (nx + 1) * row;
    const int64_t fv = i + nx * (j + (ny + 1) * k);
    double sum = 0.0;
    if (cu[fu] != 0.0) sum += cu[fu] * x[c - 1];
    if (cu[fu + 1] != 0.0) sum += cu[fu + 1] * x[c + 1];
    if (cv[fv] != 0.0) sum += cv[fv] * x[c - nx];
    if (cv[fv + nx] != 0.0) sum += cv[fv + nx] * x[c + nx];
    if (cw[c] != 0.0) sum += cw[c] * x[c - sz];
    if (cw[c + sz] != 0.0) sum += cw[c + sz] * x[c + sz];
    return sum;
  }
};

void halfSweep(TaskSystem& tasks, const Stencil& s, const double* b, double* x, int colour) {
  parallelFor(tasks, s.rows(), s.rowGrain(), [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t j = row % s.ny, k = row / s.ny;
      for (int64_t i = (j + k + colour) & 1; i < s.nx; i += 2) {
        const int64_t c = i + s.nx * row;
        const double d = s.diagonal[c];
        if (d > 0.0) x[c] = (b[c] + s.neighbourSum(row, i, x)) / d;
      }
    }
  });
}

}  // namespace

void smoothRedBlack(TaskSystem& tasks, const CutCellPoisson& op, const double* b, double* x, bool reverse) {
  const Stencil s(op);
  halfSweep(tasks, s, b, x, reverse ? 1 : 0);
  halfSweep(tasks, s, b, x, reverse ? 0 : 1);
}

void smoothJacobi(TaskSystem& tasks, const CutCellPoisson& op, const double* b, double* x, double* scratch,
                  double weight) {
  const Stencil s(op);
  parallelFor(tasks, s.rows(), s.rowGrain(), [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row)
      for (int64_t i = 0; i < s.nx; ++i) {
        const int64_t c = i + s.nx * row;
        const double d = s.diagonal[c];
        scratch[c] = d > 0.0 ? x[c] + weight * (b[c] + s.neighbourSum(row, i, x) - d * x[c]) / d : 0.0;
      }
  });
  const int64_t cells = s.rows() * s.nx;
  parallelFor(tasks, cells, kCellsPerChunk, [&](int64_t begin, int64_t end) {
    for (int64_t c = begin; c < end; ++c) x[c] = scratch[c];
  });
}

void computeResidual(TaskSystem& tasks, const CutCellPoisson& op, const double* b, const double* x, double* r) {
  const Stencil s(op);
  parallelFor(tasks, s.rows(), s.rowGrain(), [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row)
      for (int64_t i = 0; i < s.nx; ++i) {
        const int64_t c = i + s.nx * row;
        const double d = s.diagonal[c];
        r[c] = d > 0.0 ? b[c] + s.neighbourSum(row, i, x) - d * x[c] : 0.0;
      }
  });
}

}  // namespace vp

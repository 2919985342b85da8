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

void smoothRedBlackCells(TaskSystem& tasks, const CutCellPoisson& op, const std::vector<int64_t>* byColour,
                         const double* b, double* x, bool reverse) {
  const Stencil s(op);
  for (int half = 0; half < 2; ++half) {
    const std::vector<int64_t>& list = byColour[reverse ? 1 - half : half];
    parallelFor(tasks, static_cast<int64_t>(list.size()), kCellsPerChunk, [&](int64_t begin, int64_t end) {
      for (int64_t n = begin; n < end; ++n) {
        const int64_t c = list[static_cast<size_t>(n)];
        x[c] = (b[c] + s.neighbourSum(c / s.nx, c % s.nx, x)) / s.diagonal[c];
      }
    });
  }
}

void findBoundaryCells(const CutCellPoisson& op, double fullCoupling, std::vector<int64_t> byColour[2]) {
  const Stencil s(op);
  const int64_t cells = s.rows() * s.nx;
  std::vector<uint8_t> cut(static_cast<size_t>(cells), 0);
  for (int64_t c = 0; c < cells; ++c) {
    const double d = s.diagonal[c];
    if (!(d > 0.0)) continue;
    const int64_t row = c / s.nx, i = c % s.nx, j = row % s.ny, k = row / s.ny;
    const int64_t fu = i + (s.nx + 1) * row, fv = i + s.nx * (j + (s.ny + 1) * k);
    // Domain-boundary faces (coupling 0 on every level) are planar and grid-aligned, which the
    // transfers handle (multigrid_transfer.h); only faces inside the grid count.
    const bool inside[6] = {i > 0, i + 1 < s.nx, j > 0, j + 1 < s.ny, k > 0, k + 1 < s.nz};
    const double faces[6] = {s.cu[fu], s.cu[fu + 1], s.cv[fv], s.cv[fv + s.nx], s.cw[c], s.cw[c + s.sz]};
    bool isCut = false, onDomainBoundary = false;
    double couplings = 0.0;
    for (int f = 0; f < 6; ++f) {
      couplings += faces[f];
      onDomainBoundary = onDomainBoundary || !inside[f];
      isCut = isCut || (inside[f] && faces[f] < fullCoupling * (1.0 - 1e-12));
    }
    // A Dirichlet part away from the domain sides is a free-surface face.
    isCut = isCut || (!onDomainBoundary && d > couplings * (1.0 + 1e-12));
    cut[static_cast<size_t>(c)] = isCut ? 1 : 0;
  }
  byColour[0].clear();
  byColour[1].clear();
  for (int64_t c = 0; c < cells; ++c) {
    if (!(s.diagonal[c] > 0.0)) continue;
    const int64_t row = c / s.nx, i = c % s.nx, j = row % s.ny, k = row / s.ny;
    bool near = cut[static_cast<size_t>(c)] != 0;
    near = near || (i > 0 && cut[static_cast<size_t>(c - 1)]) || (i + 1 < s.nx && cut[static_cast<size_t>(c + 1)]);
    near = near || (j > 0 && cut[static_cast<size_t>(c - s.nx)]) || (j + 1 < s.ny && cut[static_cast<size_t>(c + s.nx)]);
    near = near || (k > 0 && cut[static_cast<size_t>(c - s.sz)]) || (k + 1 < s.nz && cut[static_cast<size_t>(c + s.sz)]);
    if (near) byColour[(i + j + k) & 1].push_back(c);
  }
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

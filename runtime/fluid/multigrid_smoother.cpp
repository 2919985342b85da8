// Red-black Gauss-Seidel, damped Jacobi and the residual of a multigrid level (see
// multigrid_smoother.h).
#include "fluid/multigrid_smoother.h"

#include <algorithm>

#include "core/parallel_for.h"

namespace vp {
namespace {

constexpr int64_t kCellsPerChunk = 4096;
// Boundary lists are short (about 1% of the cells at 128^3) and swept 16 times per level and
// cycle: chunks this large keep lists below it on the calling thread, where a dispatch to the
// pool would cost more than the sweep.
constexpr int64_t kBoundaryCellsPerChunk = 16384;
// Slabs of planes a fused red-black sweep is cut into (fixed, so the work split never depends
// on the worker count; the values never depend on it at all).
constexpr int64_t kSlabsPerSweep = 16;

// Raw arrays and strides of a level.
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
};

// One grid row (j, k) of a level with its neighbour rows, set up once per row so the cell loop
// has no index arithmetic beyond i (integer divisions per cell cost more than the memory
// traffic). A neighbour row outside the grid is replaced by the row itself: its face coupling
// is 0, so the product vanishes without a branch.
struct Row {
  const double* cu;      // cu[i], cu[i + 1]: the cell's -x and +x faces
  const double* cvLow;   // -y faces of the row's cells
  const double* cvHigh;  // +y faces
  const double* cwLow;   // -z faces
  const double* cwHigh;  // +z faces
  const double* diagonal;
  const double* x;
  const double* xDown;   // row j - 1
  const double* xUp;     // row j + 1
  const double* xBack;   // row k - 1
  const double* xFront;  // row k + 1
  int64_t nx;

  Row(const Stencil& s, int64_t j, int64_t k, const double* values) : nx(s.nx) {
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
  double neighbourSum(int64_t i) const {
    const double left = i > 0 ? x[i - 1] : 0.0;
    const double right = i + 1 < nx ? x[i + 1] : 0.0;
    return cu[i] * left + cu[i + 1] * right + cvLow[i] * xDown[i] + cvHigh[i] * xUp[i] + cwLow[i] * xBack[i] +
           cwHigh[i] * xFront[i];
  }
};

// Calls body(row, i0 of the row's cells) for every row in parallel.
template <class Body>
void forEachRow(TaskSystem& tasks, const Stencil& s, const Body& body) {
  parallelFor(tasks, s.rows(), s.rowGrain(), [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) body(row % s.ny, row / s.ny, s.nx * row);
  });
}

// Gauss-Seidel update of the cells of one colour in one row. kFromZero: the sweep starts from
// x = 0 without x having been cleared, so the first colour ignores its neighbours (they are 0)
// and both colours write every cell, non-fluid ones included (0), which makes a separate
// clearing pass unnecessary.
template <bool kFromZero>
void updateRow(const Stencil& s, int64_t j, int64_t k, const double* b, double* x, int colour, bool firstColour) {
  const Row r(s, j, k, x);
  const int64_t c0 = s.nx * (j + s.ny * k);
  double* xr = x + c0;
  const double* br = b + c0;
  for (int64_t i = (j + k + colour) & 1; i < s.nx; i += 2) {
    const double d = r.diagonal[i];
    if (kFromZero) xr[i] = d > 0.0 ? (br[i] + (firstColour ? 0.0 : r.neighbourSum(i))) / d : 0.0;
    else if (d > 0.0) xr[i] = (br[i] + r.neighbourSum(i)) / d;
  }
}

template <bool kFromZero>
void updatePlane(const Stencil& s, int64_t k, const double* b, double* x, int colour, bool firstColour) {
  for (int64_t j = 0; j < s.ny; ++j) updateRow<kFromZero>(s, j, k, b, x, colour, firstColour);
}

// Both colours in one pass over memory: plane k gets its first colour, then plane k - 1 its
// second (which needs the first colour on k - 2, k - 1 and k: all done), so each plane is
// streamed once while it is still in cache instead of twice. The values are exactly those of
// two full half-sweeps. Parallel over slabs of planes: the first and the last plane of a slab
// take their second colour in a second phase, because in the first phase the neighbouring
// slabs' first-colour updates still read those planes' old second-colour values, and then
// the neighbours' first colour is all done.
template <bool kFromZero>
void fusedSweep(TaskSystem& tasks, const Stencil& s, const double* b, double* x, int first) {
  const int second = 1 - first;
  const int64_t slabPlanes = std::max<int64_t>(2, (s.nz + kSlabsPerSweep - 1) / kSlabsPerSweep);
  const int64_t slabs = (s.nz + slabPlanes - 1) / slabPlanes;
  auto slabRange = [&](int64_t slab, int64_t* k0, int64_t* k1) {
    *k0 = slab * slabPlanes;
    *k1 = std::min(s.nz, *k0 + slabPlanes);
  };
  parallelFor(tasks, slabs, 1, [&](int64_t begin, int64_t end) {
    for (int64_t slab = begin; slab < end; ++slab) {
      int64_t k0, k1;
      slabRange(slab, &k0, &k1);
      for (int64_t k = k0; k < k1; ++k) {
        updatePlane<kFromZero>(s, k, b, x, first, true);
        if (k - 1 > k0) updatePlane<kFromZero>(s, k - 1, b, x, second, false);
      }
    }
  });
  parallelFor(tasks, slabs, 1, [&](int64_t begin, int64_t end) {
    for (int64_t slab = begin; slab < end; ++slab) {
      int64_t k0, k1;
      slabRange(slab, &k0, &k1);
      updatePlane<kFromZero>(s, k0, b, x, second, false);
      if (k1 - 1 > k0) updatePlane<kFromZero>(s, k1 - 1, b, x, second, false);
    }
  });
}

}  // namespace

void smoothRedBlack(TaskSystem& tasks, const CutCellPoisson& op, const double* b, double* x, bool reverse,
                    bool fromZero) {
  const Stencil s(op);
  if (fromZero) fusedSweep<true>(tasks, s, b, x, reverse ? 1 : 0);
  else fusedSweep<false>(tasks, s, b, x, reverse ? 1 : 0);
}

void smoothJacobi(TaskSystem& tasks, const CutCellPoisson& op, const double* b, double* x, double* scratch,
                  double weight, int sweeps, bool fromZero) {
  const Stencil s(op);
  // Ping-pong between x and scratch, so a sweep is one pass and only an odd count copies back.
  // From zero the first sweep is w D^-1 b: no neighbour reads, nothing to clear.
  const double* in = x;
  double* out = fromZero ? x : scratch;  // the sweep from zero reads nothing: it may write x
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    const bool first = fromZero && sweep == 0;
    forEachRow(tasks, s, [&](int64_t j, int64_t k, int64_t c0) {
      const Row r(s, j, k, first ? nullptr : in);
      for (int64_t i = 0; i < s.nx; ++i) {
        const double d = r.diagonal[i];
        if (!(d > 0.0)) out[c0 + i] = 0.0;
        else if (first) out[c0 + i] = weight * b[c0 + i] / d;
        else out[c0 + i] = r.x[i] + weight * (b[c0 + i] + r.neighbourSum(i) - d * r.x[i]) / d;
      }
    });
    in = out;
    out = out == x ? scratch : x;
  }
  if (in != x) {
    parallelFor(tasks, s.rows() * s.nx, kCellsPerChunk, [&](int64_t begin, int64_t end) {
      for (int64_t c = begin; c < end; ++c) x[c] = in[c];
    });
  }
}

void smoothRedBlackCells(TaskSystem& tasks, const CutCellPoisson& op, const BoundaryCellLists& byColour,
                         const double* b, double* x, bool reverse) {
  const Stencil s(op);
  for (int half = 0; half < 2; ++half) {
    const std::vector<BoundaryCell>& list = byColour[static_cast<size_t>(reverse ? 1 - half : half)];
    parallelFor(tasks, static_cast<int64_t>(list.size()), kBoundaryCellsPerChunk, [&](int64_t begin, int64_t end) {
      for (int64_t n = begin; n < end; ++n) {
        const BoundaryCell& e = list[static_cast<size_t>(n)];
        const int64_t c = e.cell;
        const double sum = s.cu[e.faceU] * x[e.neighbour[0]] + s.cu[e.faceU + 1] * x[e.neighbour[1]] +
                           s.cv[e.faceV] * x[e.neighbour[2]] + s.cv[e.faceV + s.nx] * x[e.neighbour[3]] +
                           s.cw[c] * x[e.neighbour[4]] + s.cw[c + s.sz] * x[e.neighbour[5]];
        x[c] = (b[c] + sum) / s.diagonal[c];
      }
    });
  }
}

void findBoundaryCells(TaskSystem& tasks, const CutCellPoisson& op, double fullCoupling,
                       BoundaryCellLists* byColour) {
  const Stencil s(op);
  std::vector<uint8_t> cut(static_cast<size_t>(s.rows() * s.nx), 0);
  forEachRow(tasks, s, [&](int64_t j, int64_t k, int64_t c0) {
    const Row r(s, j, k, nullptr);
    for (int64_t i = 0; i < s.nx; ++i) {
      const double d = r.diagonal[i];
      if (!(d > 0.0)) continue;
      // Domain-boundary faces (coupling 0 on every level) are planar and grid-aligned, which
      // the transfers handle (multigrid_transfer.h); only faces inside the grid count.
      const bool inside[6] = {i > 0, i + 1 < s.nx, j > 0, j + 1 < s.ny, k > 0, k + 1 < s.nz};
      const double faces[6] = {r.cu[i], r.cu[i + 1], r.cvLow[i], r.cvHigh[i], r.cwLow[i], r.cwHigh[i]};
      bool isCut = false, onDomainBoundary = false;
      double couplings = 0.0;
      for (int f = 0; f < 6; ++f) {
        couplings += faces[f];
        onDomainBoundary = onDomainBoundary || !inside[f];
        isCut = isCut || (inside[f] && faces[f] < fullCoupling * (1.0 - 1e-12));
      }
      // A Dirichlet part away from the domain sides is a free-surface face.
      isCut = isCut || (!onDomainBoundary && d > couplings * (1.0 + 1e-12));
      cut[static_cast<size_t>(c0 + i)] = isCut ? 1 : 0;
    }
  });
  for (std::vector<BoundaryCell>& list : *byColour) list.clear();
  // Serial, in cell order, so the lists (and the sweeps' results) never depend on the workers.
  const int64_t step[6] = {-1, 1, -s.nx, s.nx, -s.sz, s.sz};
  for (int64_t k = 0; k < s.nz; ++k)
    for (int64_t j = 0; j < s.ny; ++j) {
      const int64_t row = j + s.ny * k;
      for (int64_t i = 0; i < s.nx; ++i) {
        const int64_t c = i + s.nx * row;
        if (!(s.diagonal[c] > 0.0)) continue;
        const bool inside[6] = {i > 0, i + 1 < s.nx, j > 0, j + 1 < s.ny, k > 0, k + 1 < s.nz};
        bool near = cut[static_cast<size_t>(c)] != 0;
        for (int f = 0; f < 6; ++f) near = near || (inside[f] && cut[static_cast<size_t>(c + step[f])]);
        if (!near) continue;
        BoundaryCell e;
        e.cell = c;
        e.faceU = i + (s.nx + 1) * row;
        e.faceV = i + s.nx * (j + (s.ny + 1) * k);
        for (int f = 0; f < 6; ++f) e.neighbour[f] = inside[f] ? c + step[f] : c;
        (*byColour)[static_cast<size_t>((i + j + k) & 1)].push_back(e);
      }
    }
}

void computeResidual(TaskSystem& tasks, const CutCellPoisson& op, const double* b, const double* x, double* r) {
  const Stencil s(op);
  forEachRow(tasks, s, [&](int64_t j, int64_t k, int64_t c0) {
    const Row row(s, j, k, x);
    for (int64_t i = 0; i < s.nx; ++i) {
      const double d = row.diagonal[i];
      r[c0 + i] = d > 0.0 ? b[c0 + i] + row.neighbourSum(i) - d * row.x[i] : 0.0;
    }
  });
}

}  // namespace vp

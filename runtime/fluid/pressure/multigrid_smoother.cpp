// Red-black Gauss-Seidel, damped Jacobi and the residual of a multigrid level (see
// multigrid_smoother.h).
#include "fluid/pressure/multigrid_smoother.h"

#include <algorithm>

#include "core/parallel_for.h"
#include "fluid/pressure/poisson_rows.h"

namespace vp {
namespace {

using poisson_rows::forEachRow;
using poisson_rows::gaussSeidelRow;
using poisson_rows::jacobiRow;
using poisson_rows::kCellsPerChunk;
using poisson_rows::residualRow;
using poisson_rows::Row;
using poisson_rows::SweepStart;
using poisson_rows::Stencil;

// Boundary lists are a small part of the grid and are swept `boundarySweeps` times per level
// and cycle: chunks this large keep lists below it on the calling thread, where a dispatch to
// the pool would cost more than the sweep.
constexpr int64_t kBoundaryCellsPerChunk = 16384;
// Slabs of planes a fused red-black sweep is cut into (fixed, so the work split never depends
// on the worker count; the values never depend on it at all).
constexpr int64_t kSlabsPerSweep = 16;

// kFromZero: the sweep starts from x = 0 without x having been cleared (SweepStart).
template <bool kFromZero, class T>
void updatePlane(const Stencil<T>& s, int64_t k, const T* b, T* x, int colour, bool firstColour) {
  const SweepStart start = !kFromZero     ? SweepStart::Continue
                           : firstColour ? SweepStart::FromZeroFirstColour
                                         : SweepStart::FromZeroSecondColour;
  for (int64_t j = 0; j < s.ny; ++j) gaussSeidelRow(s, j, k, b, x, colour, start);
}

// Both colours in one pass over memory: plane k gets its first colour, then plane k - 1 its
// second (which needs the first colour on k - 2, k - 1 and k: all done), so each plane is
// streamed once while it is still in cache instead of twice. The values are exactly those of
// two full half-sweeps. Parallel over slabs of planes: the first and the last plane of a slab
// take their second colour in a second phase, because in the first phase the neighbouring
// slabs' first-colour updates still read those planes' old second-colour values, and then
// the neighbours' first colour is all done.
template <bool kFromZero, class T>
void fusedSweep(TaskSystem& tasks, const Stencil<T>& s, const T* b, T* x, int first) {
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

template <class T>
void smoothRedBlack(TaskSystem& tasks, const PoissonCoefficients<T>& op, const T* b, T* x, bool reverse,
                    bool fromZero) {
  const Stencil<T> s(op);
  if (fromZero) fusedSweep<true>(tasks, s, b, x, reverse ? 1 : 0);
  else fusedSweep<false>(tasks, s, b, x, reverse ? 1 : 0);
}

template <class T>
void smoothJacobi(TaskSystem& tasks, const PoissonCoefficients<T>& op, const T* b, T* x, T* scratch, double weight,
                  int sweeps, bool fromZero) {
  const Stencil<T> s(op);
  const T w = static_cast<T>(weight);
  // Ping-pong between x and scratch, so a sweep is one pass and only an odd count copies back.
  // From zero the first sweep is w D^-1 b: no neighbour reads, nothing to clear.
  const T* in = x;
  T* out = fromZero ? x : scratch;  // the sweep from zero reads nothing: it may write x
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    const bool first = fromZero && sweep == 0;
    forEachRow(tasks, s, [&](int64_t j, int64_t k, int64_t) { jacobiRow(s, j, k, b, first ? nullptr : in, out, w); });
    in = out;
    out = out == x ? scratch : x;
  }
  if (in != x) {
    parallelFor(tasks, s.rows() * s.nx, kCellsPerChunk, [&](int64_t begin, int64_t end) {
      for (int64_t c = begin; c < end; ++c) x[c] = in[c];
    });
  }
}

void smoothBoundaryCells(TaskSystem& tasks, const PoissonCoefficients<float>& op, const BoundaryCellLists& cells,
                         const float* b, float* x, bool reverse, int sweeps, BoundarySweepValues* scratch) {
  const int64_t count = cells.count();
  if (count == 0 || sweeps <= 0) return;
  const int64_t nx = op.grid.nx, sz = nx * op.grid.ny;
  const int64_t step[6] = {-1, 1, -nx, nx, -sz, sz};
  const int64_t offset[2] = {0, static_cast<int64_t>(cells.byColour[0].size())};
  scratch->values.resize(static_cast<size_t>(7 * count));
  scratch->rhs.resize(static_cast<size_t>(count));
  float* values = scratch->values.data();
  float* rhs = scratch->rhs.data();
  const int32_t* reads = cells.reads.data();
  auto forEachEntry = [&](int colour, const auto& body) {
    const Array<BoundaryCell>& list = cells.byColour[static_cast<size_t>(colour)];
    parallelFor(tasks, static_cast<int64_t>(list.size()), kBoundaryCellsPerChunk, [&](int64_t begin, int64_t end) {
      for (int64_t n = begin; n < end; ++n) body(list[static_cast<size_t>(n)], offset[colour] + n);
    });
  };
  for (int colour = 0; colour < 2; ++colour)
    forEachEntry(colour, [&](const BoundaryCell& e, int64_t entry) {
      values[entry] = x[e.cell];
      rhs[entry] = b[e.cell];
      for (int f = 0; f < 6; ++f) {
        const int32_t at = reads[6 * entry + f];
        if (at >= count) values[at] = x[e.cell + step[f]];
      }
    });
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (int half = 0; half < 2; ++half)
      forEachEntry(reverse ? 1 - half : half, [&](const BoundaryCell& e, int64_t entry) {
        values[entry] = kernels::boundaryCellUpdate(e, reads + 6 * entry, values, rhs[entry]);
      });
  for (int colour = 0; colour < 2; ++colour)
    forEachEntry(colour, [&](const BoundaryCell& e, int64_t entry) { x[e.cell] = values[entry]; });
}

namespace {

// BoundaryCellLists::reads of entries [begin, end) of one colour's list, from the lists. A
// face couples cells of different colours, so a listed neighbour is in the other list; both
// lists are in cell order, so each face's neighbours are found by one walk along the other list.
void linkBoundaryCells(const Stencil<double>& s, int colour, BoundaryCellLists* cells, int64_t begin, int64_t end) {
  if (begin >= end) return;
  const int64_t count = cells->count(), reds = static_cast<int64_t>(cells->byColour[0].size());
  const int64_t step[6] = {-1, 1, -s.nx, s.nx, -s.sz, s.sz};
  const Array<BoundaryCell>& own = cells->byColour[static_cast<size_t>(colour)];
  const Array<BoundaryCell>& other = cells->byColour[static_cast<size_t>(1 - colour)];
  const int64_t ownOffset = colour == 0 ? 0 : reds, otherOffset = colour == 0 ? reds : 0;
  auto cellAfter = [](const BoundaryCell& c, int64_t cell) { return c.cell < cell; };
  for (int f = 0; f < 6; ++f) {
    auto walk =
        std::lower_bound(other.begin(), other.end(), own[static_cast<size_t>(begin)].cell + step[f], cellAfter);
    for (int64_t n = begin; n < end; ++n) {
      const BoundaryCell& e = own[static_cast<size_t>(n)];
      const int64_t entry = ownOffset + n;
      int64_t at = count + 6 * entry + f;
      if (e.coupling[f] == 0.0f) {
        at = entry;
      } else {
        const int64_t neighbour = e.cell + step[f];
        while (walk != other.end() && walk->cell < neighbour) ++walk;
        if (walk != other.end() && walk->cell == neighbour) at = otherOffset + (walk - other.begin());
      }
      cells->reads[static_cast<size_t>(6 * entry + f)] = static_cast<int32_t>(at);
    }
  }
}

// Linking a listed cell (six steps of walks along a list) costs about this many samples.
constexpr int64_t kSamplesPerLinkedCell = 4;
constexpr int64_t kLinkGrain = 256;

}  // namespace

void findBoundaryCells(TaskSystem& tasks, const CutCellPoisson& op, double fullCoupling,
                       BoundaryCellLists* cells) {
  SlabPasses passes(tasks);
  Array<uint8_t> cut;
  appendFindBoundaryCells(op, fullCoupling, cells, &cut, &passes);
  passes.runAll();
}

void appendFindBoundaryCells(const CutCellPoisson& op, double fullCoupling, BoundaryCellLists* cells,
                             Array<uint8_t>* cutCells, SlabPasses* passes) {
  const CutCellPoisson* level = &op;
  passes->addStep([level, fullCoupling, cells, cutCells, passes] {
    const Stencil<double> s(*level);
    cutCells->resize(static_cast<size_t>(s.rows() * s.nx));
    for (Array<BoundaryCell>& list : cells->byColour) list.clear();
    uint8_t* cut = cutCells->data();
    passes->addParallel(s.rows(), s.nx, s.rowGrain(), [s, cut, fullCoupling](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) {
        const int64_t j = row % s.ny, k = row / s.ny, c0 = s.nx * row;
        const Row<double> r(s, j, k, nullptr);
        for (int64_t i = 0; i < s.nx; ++i) {
          const double d = r.diagonal[i];
          cut[c0 + i] = 0;
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
          cut[c0 + i] = isCut ? 1 : 0;
        }
      }
    });
    // Serial, rows in order, so the lists (and the sweeps' results) never depend on the workers
    // or on the slabs.
    passes->addSerial(s.rows(), s.nx, [s, cut, cells](int64_t begin, int64_t end) {
      const int64_t step[6] = {-1, 1, -s.nx, s.nx, -s.sz, s.sz};
      for (int64_t row = begin; row < end; ++row) {
        const int64_t j = row % s.ny, k = row / s.ny;
        for (int64_t i = 0; i < s.nx; ++i) {
          const int64_t c = i + s.nx * row;
          if (!(s.diagonal[c] > 0.0)) continue;
          const bool inside[6] = {i > 0, i + 1 < s.nx, j > 0, j + 1 < s.ny, k > 0, k + 1 < s.nz};
          bool near = cut[c] != 0;
          for (int f = 0; f < 6; ++f) near = near || (inside[f] && cut[c + step[f]]);
          if (!near) continue;
          const Row<double> r(s, j, k, nullptr);
          const double faces[6] = {r.cu[i], r.cu[i + 1], r.cvLow[i], r.cvHigh[i], r.cwLow[i], r.cwHigh[i]};
          BoundaryCell e;
          e.cell = static_cast<int32_t>(c);
          // Domain-side faces hold coupling 0 already (cut_cell_poisson.h); `inside` makes sure.
          for (int f = 0; f < 6; ++f) e.coupling[f] = inside[f] ? static_cast<float>(faces[f]) : 0.0f;
          e.inverseDiagonal = static_cast<float>(1.0 / s.diagonal[c]);
          cells->byColour[static_cast<size_t>((i + j + k) & 1)].push_back(e);
        }
      }
    });
    passes->addStep([s, cells, passes] {
      cells->reads.resize(static_cast<size_t>(6 * cells->count()));
      for (int colour = 0; colour < 2; ++colour)
        passes->addParallel(static_cast<int64_t>(cells->byColour[static_cast<size_t>(colour)].size()),
                            kSamplesPerLinkedCell, kLinkGrain, [s, colour, cells](int64_t begin, int64_t end) {
                              linkBoundaryCells(s, colour, cells, begin, end);
                            });
    });
  });
}

template <class T>
void computeResidual(TaskSystem& tasks, const PoissonCoefficients<T>& op, const T* b, const T* x, T* r) {
  const Stencil<T> s(op);
  forEachRow(tasks, s, [&](int64_t j, int64_t k, int64_t first) { residualRow(s, j, k, b, x, r + first); });
}

#define VP_INSTANTIATE_SMOOTHERS(T)                                                                         \
  template void smoothRedBlack<T>(TaskSystem&, const PoissonCoefficients<T>&, const T*, T*, bool, bool);         \
  template void smoothJacobi<T>(TaskSystem&, const PoissonCoefficients<T>&, const T*, T*, T*, double, int, bool); \
  template void computeResidual<T>(TaskSystem&, const PoissonCoefficients<T>&, const T*, const T*, T*);
VP_INSTANTIATE_SMOOTHERS(double)
VP_INSTANTIATE_SMOOTHERS(float)
#undef VP_INSTANTIATE_SMOOTHERS

}  // namespace vp

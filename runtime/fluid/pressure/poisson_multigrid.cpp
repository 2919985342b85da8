// Multigrid hierarchy and V-cycle for the cut-cell pressure operator (see poisson_multigrid.h).
#include "fluid/pressure/poisson_multigrid.h"

#include <algorithm>
#include <cstdint>

#include "core/parallel_for.h"
#include "fluid/pressure/multigrid_coarsening.h"
#include "fluid/pressure/multigrid_transfer.h"

namespace vp {
namespace {

constexpr int64_t kValueGrain = 4096;
constexpr int64_t kRowGrain = 16;
// Levels with fewer cells run the V-cycle's passes on the calling thread: a pass over a level
// this small costs less than handing it to the workers and waiting for them (the coarsest
// level's sweeps alone are dozens of passes per cycle).
constexpr int64_t kInlineLevelCells = 32768;

// `sweeps` sweeps (adjoint order when `adjoint`); `fromZero`: x holds anything and the smoothing
// starts from 0 (both smoothers fold the clearing into their first sweep).
void smooth(TaskSystem& tasks, const PoissonCoefficients<float>& op, const MultigridSettings& s, const float* b,
            float* x, Array<float>& scratch, int sweeps, bool adjoint, bool fromZero) {
  if (s.smoother == PoissonSmoother::DampedJacobi) {
    smoothJacobi(tasks, op, b, x, scratch.data(), s.jacobiWeight, sweeps, fromZero);
    return;
  }
  for (int i = 0; i < sweeps; ++i) smoothRedBlack(tasks, op, b, x, adjoint, fromZero && i == 0);
}

// Pre-smoothing (from zero): full sweeps then boundary sweeps; post-smoothing: the adjoint, in
// reverse order.
void smoothLevel(TaskSystem& tasks, const PoissonCoefficients<float>& op, const MultigridSettings& s,
                 const BoundaryCellLists& boundary, const float* b, float* x, Array<float>& scratch,
                 BoundarySweepValues* boundaryValues, bool post) {
  if (!post) smooth(tasks, op, s, b, x, scratch, s.sweeps, false, true);
  smoothBoundaryCells(tasks, op, boundary, b, x, post, s.boundarySweeps, boundaryValues);
  if (post) smooth(tasks, op, s, b, x, scratch, s.sweeps, true, false);
}

template <class From, class To>
void convertValues(const From* from, To* to, int64_t begin, int64_t end) {
  for (int64_t i = begin; i < end; ++i) to[i] = static_cast<To>(from[i]);
}

template <class From, class To>
void convertVector(TaskSystem& tasks, int64_t count, const From* from, To* to) {
  parallelFor(tasks, count, kValueGrain, [&](int64_t begin, int64_t end) { convertValues(from, to, begin, end); });
}

// A pass converting `from` into `to` (sized by it when the pass is added).
template <class From, class To>
void addConversion(SlabPasses* passes, const Array<From>* from, Array<To>* to) {
  to->resize(from->size());
  passes->addParallel(static_cast<int64_t>(from->size()), 1, kValueGrain, [from, to](int64_t begin, int64_t end) {
    convertValues(from->data(), to->data(), begin, end);
  });
}

// Converts the rows of `in` raised in `changed` into `out`: a cell row's diagonal and the face
// rows it owns (changed_rows.h); everything when `changed` is null or says all.
void addSinglePrecision(SlabPasses* passes, const CutCellPoisson* in, PoissonCoefficients<float>* out,
                        const ChangedRows* changed) {
  passes->addStep([passes, in, out, changed] {
    const bool update = changed != nullptr && !changed->all && sameGrid(out->grid, in->grid) &&
                        out->diagonal.size() == in->diagonal.size();
    out->grid = in->grid;
    out->rowSpan = in->rowSpan;
    if (!update) {
      for (int a = 0; a < 3; ++a) addConversion(passes, &in->coupling[a], &out->coupling[a]);
      addConversion(passes, &in->diagonal, &out->diagonal);
      return;
    }
    const int64_t nx = in->grid.nx, ny = in->grid.ny, nz = in->grid.nz;
    passes->addParallel(ny * nz, 4 * nx, kRowGrain, [=](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) {
        if (!changed->raised(row)) continue;
        convertValues(in->diagonal.data(), out->diagonal.data(), nx * row, nx * (row + 1));
        for (int a = 0; a < 3; ++a) {
          const int64_t length = nx + (a == 0);
          const OwnedFaceRows owned = ownedFaceRows(a, row, ny, nz);
          for (int r = 0; r < owned.count; ++r)
            convertValues(in->coupling[a].data(), out->coupling[a].data(), length * owned.row[r],
                          length * (owned.row[r] + 1));
        }
      }
    });
  });
}

// The prolongation scales of fine level `fine` (multigrid_transfer.h) in single precision:
// the rows whose inputs changed, the fine row raised or a coarse row of its stencil; all of
// them when either has no flags or says all.
void addProlongationScale(SlabPasses* passes, const CutCellPoisson* fine, const CutCellPoisson* coarse,
                          const TransferSides* sides, const ChangedRows* fineChanged,
                          const ChangedRows* coarseChanged, Array<float>* out) {
  passes->addStep([=] {
    const int64_t nx = fine->grid.nx, ny = fine->grid.ny, rows = ny * fine->grid.nz;
    const int64_t cy = coarse->grid.ny, cz = coarse->grid.nz;
    const bool update = fineChanged != nullptr && coarseChanged != nullptr && !fineChanged->all &&
                        !coarseChanged->all && out->size() == static_cast<size_t>(nx * rows);
    out->resize(static_cast<size_t>(nx * rows));
    passes->addParallel(rows, nx, kRowGrain, [=](int64_t begin, int64_t end) {
      Array<double> scale(static_cast<size_t>(nx));
      for (int64_t row = begin; row < end; ++row) {
        bool reached = !update || fineChanged->raised(row);
        const int64_t J = (row % ny) / 2, K = (row / ny) / 2;
        for (int64_t z = std::max<int64_t>(0, K - 1); z <= std::min(cz - 1, K + 1) && !reached; ++z)
          for (int64_t y = std::max<int64_t>(0, J - 1); y <= std::min(cy - 1, J + 1); ++y)
            reached = reached || coarseChanged->raised(y + cy * z);
        if (!reached) continue;
        prolongationScaleRow(*fine, *coarse, *sides, row, scale.data());
        convertValues(scale.data(), out->data() + nx * row, 0, nx);
      }
    });
  });
}

bool sameSetup(const MultigridSettings& a, const MultigridSettings& b) {
  return a.coarsening == b.coarsening && a.smoother == b.smoother && a.sweeps == b.sweeps &&
         a.jacobiWeight == b.jacobiWeight && a.coarsestSize == b.coarsestSize &&
         a.coarsestSweeps == b.coarsestSweeps && a.boundarySweeps == b.boundarySweeps;
}

bool canCoarsen(const MacGridSpec& g, int coarsestSize) {
  return std::min({g.nx, g.ny, g.nz}) >= 2 * coarsestSize;
}

}  // namespace

Status checkPoissonMultigrid(const MacGridSpec& fineGrid, const MultigridSettings& settings) {
  if (settings.sweeps < 1 || settings.coarsestSweeps < 1 || settings.boundarySweeps < 0)
    return fail(Status::InvalidArgument,
                "multigrid: sweeps = %d and coarsestSweeps = %d must be >= 1, boundarySweeps = %d >= 0",
                settings.sweeps, settings.coarsestSweeps, settings.boundarySweeps);
  if (settings.coarsestSize < 1)
    return fail(Status::InvalidArgument, "multigrid: coarsestSize = %d must be >= 1", settings.coarsestSize);
  if (!(settings.jacobiWeight > 0.0 && settings.jacobiWeight <= 1.0))
    return fail(Status::InvalidArgument, "multigrid: jacobiWeight = %g must lie in (0, 1]", settings.jacobiWeight);
  // Boundary cell lists index cells with 32 bits (multigrid_smoother.h).
  if (static_cast<int64_t>(fineGrid.nx) * fineGrid.ny * fineGrid.nz > INT32_MAX)
    return fail(Status::InvalidArgument, "multigrid: grid (%d, %d, %d) has too many cells for 32-bit indices",
                fineGrid.nx, fineGrid.ny, fineGrid.nz);
  return Status::Ok;
}

Status buildPoissonMultigrid(TaskSystem& tasks, const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides,
                             const MultigridSettings& settings, PoissonMultigrid* mg) {
  if (mg == nullptr) return fail(Status::InvalidArgument, "multigrid: output is null");
  VP_TRY(checkPoissonMultigrid(fine.grid, settings));
  SlabPasses passes(tasks);
  appendBuildPoissonMultigrid(fine, sides, settings, mg, &passes, nullptr);
  passes.runAll();
  return Status::Ok;
}

void appendBuildPoissonMultigrid(const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides,
                                 const MultigridSettings& settings, PoissonMultigrid* mg, SlabPasses* passes,
                                 ChangedRows* fineChanged) {
  const CutCellPoisson* fp = &fine;
  passes->addStep([fp, sides, settings, mg, passes, fineChanged] {
    TransferSides open;
    for (int side = 0; side < 6; ++side) open.open[side] = sides[static_cast<size_t>(side)] == DomainSide::Open;
    const bool sameSides = std::equal(open.open, open.open + 6, mg->sides.open);
    // Only the cut-cell coarsening updates; other settings or sides rebuild everything.
    const bool updatable = settings.coarsening == MultigridCoarsening::CutCell && sameSides &&
                           sameSetup(settings, mg->settings);
    if (fineChanged != nullptr && !updatable) fineChanged->raiseAll();
    mg->settings = settings;
    mg->sides = open;
    int levels = 1;
    for (MacGridSpec g = fp->grid; canCoarsen(g, settings.coarsestSize); g = coarseGridSpec(g)) ++levels;
    // resize() keeps the existing levels' buffers, so a rebuild every frame does not reallocate.
    mg->coarse.resize(static_cast<size_t>(levels - 1));
    mg->changed.resize(static_cast<size_t>(levels - 1));
    mg->coarseFloating.assign(static_cast<size_t>(levels - 1), 0);
    mg->prolongScale.resize(static_cast<size_t>(levels - 1));
    mg->single.resize(static_cast<size_t>(levels));
    mg->boundaryCells.resize(static_cast<size_t>(levels));
    mg->x.resize(static_cast<size_t>(levels));
    mg->b.resize(static_cast<size_t>(levels));
    mg->r.resize(static_cast<size_t>(levels));
    auto level = [fp, mg](int l) { return l == 0 ? fp : &mg->coarse[static_cast<size_t>(l - 1)]; };
    // Level 0's flags are the caller's (none: a rebuild).
    auto changedOf = [fineChanged, mg](int l) {
      return l == 0 ? fineChanged : &mg->changed[static_cast<size_t>(l - 1)];
    };
    for (int l = 1; l < levels; ++l) {
      const CutCellPoisson* from = level(l - 1);
      CutCellPoisson* to = &mg->coarse[static_cast<size_t>(l - 1)];
      ChangedRows* flags = changedOf(l);
      if (settings.coarsening == MultigridCoarsening::CutCell) {
        appendCoarsenCutCell(*from, to, &mg->coarseningScratch, passes, changedOf(l - 1), flags);
      } else {
        appendCoarsenVoxel(*from, sides, to, &mg->coarseningScratch, passes);
        passes->addStep([flags] { flags->raiseAll(); });
      }
      addProlongationScale(passes, from, to, &mg->sides, changedOf(l - 1), flags,
                           &mg->prolongScale[static_cast<size_t>(l - 1)]);
      passes->addStep([mg, to, l] {
        mg->coarseFloating[static_cast<size_t>(l - 1)] =
            std::any_of(to->regionFloating.begin(), to->regionFloating.end(), [](uint8_t f) { return f != 0; });
      });
    }
    for (int l = 0; l < levels; ++l)
      addSinglePrecision(passes, level(l), &mg->single[static_cast<size_t>(l)], changedOf(l));
    // Full coupling doubles per level: 4 full fine faces, halved (multigrid_coarsening.h); the
    // voxel levels' full coupling follows the same rule. A level's lists depend on it alone.
    double fullCoupling = 1.0;
    for (int l = 0; l < levels; ++l, fullCoupling *= 2.0)
      if (settings.boundarySweeps > 0)
        passes->addStep([mg, level, l, fullCoupling, flags = changedOf(l), passes] {
          if (flags == nullptr || flags->any())
            appendFindBoundaryCells(*level(l), fullCoupling, &mg->boundaryCells[static_cast<size_t>(l)],
                                    &mg->boundaryScratch, passes);
        });
    passes->addStep([mg, level, levels, fineChanged] {
      for (int l = 0; l < levels; ++l) {
        const size_t cells = level(l)->diagonal.size();
        mg->r[static_cast<size_t>(l)].resize(cells);
        mg->x[static_cast<size_t>(l)].resize(cells);
        mg->b[static_cast<size_t>(l)].resize(cells);
      }
      // Every level is up to date. A rebuild without the caller's flags leaves the coarse
      // levels' raised, so the next update with flags rebuilds too.
      if (fineChanged == nullptr) return;
      fineChanged->clear();
      for (ChangedRows& flags : mg->changed) flags.clear();
    });
  });
}

void applyPoissonMultigrid(TaskSystem& tasks, const CutCellPoisson& fine, PoissonMultigrid& mg, const double* r,
                           double* z) {
  const MultigridSettings& s = mg.settings;
  const int levels = mg.levelCount();
  auto op = [&](int l) -> const CutCellPoisson& { return l == 0 ? fine : mg.coarse[static_cast<size_t>(l - 1)]; };
  auto single = [&](int l) -> const PoissonCoefficients<float>& { return mg.single[static_cast<size_t>(l)]; };
  auto xOf = [&](int l) { return mg.x[static_cast<size_t>(l)].data(); };
  auto bOf = [&](int l) { return mg.b[static_cast<size_t>(l)].data(); };
  // Passes over level l (transfers: over the finer of their two levels) run on the workers,
  // or on the calling thread for a level under kInlineLevelCells.
  auto on = [&](int l) -> TaskSystem& {
    return static_cast<int64_t>(single(l).diagonal.size()) < kInlineLevelCells ? TaskSystem::callingThread() : tasks;
  };
  auto filter = [&](int l, float* v) {
    if (l > 0 && mg.coarseFloating[static_cast<size_t>(l - 1)]) filterCutCellPoisson(on(l), op(l), v);
  };
  auto scratchOf = [&](int l) -> Array<float>& { return mg.r[static_cast<size_t>(l)]; };
  const int64_t fineCells = static_cast<int64_t>(fine.diagonal.size());
  convertVector(tasks, fineCells, r, bOf(0));

  // Every level's x starts from 0; the first smoothing sweep clears it (smooth, fromZero).
  for (int l = 0; l + 1 < levels; ++l) {
    smoothLevel(on(l), single(l), s, mg.boundaryCells[static_cast<size_t>(l)], bOf(l), xOf(l), scratchOf(l),
                &mg.boundaryValues, false);
    float* coarseB = bOf(l + 1);
    restrictResidual(on(l), op(l), op(l + 1), mg.sides, mg.prolongScale[static_cast<size_t>(l)].data(),
                     LevelResidual<float>{&single(l), bOf(l), xOf(l)}, coarseB, &mg.restrictScratch);
    filter(l + 1, coarseB);
  }
  const int last = levels - 1;
  smooth(on(last), single(last), s, bOf(last), xOf(last), scratchOf(last), s.coarsestSweeps, false, true);
  smooth(on(last), single(last), s, bOf(last), xOf(last), scratchOf(last), s.coarsestSweeps, true, false);
  filter(last, xOf(last));
  for (int l = last - 1; l >= 0; --l) {
    prolongateAdd(on(l), op(l), op(l + 1), mg.sides, mg.prolongScale[static_cast<size_t>(l)].data(), xOf(l + 1),
                  xOf(l));
    smoothLevel(on(l), single(l), s, mg.boundaryCells[static_cast<size_t>(l)], bOf(l), xOf(l), scratchOf(l),
                &mg.boundaryValues, true);
    filter(l, xOf(l));
  }
  convertVector(tasks, fineCells, xOf(0), z);
}

}  // namespace vp

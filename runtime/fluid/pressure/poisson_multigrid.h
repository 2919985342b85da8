// Geometric multigrid V-cycle for the cut-cell pressure operator, used as the preconditioner of
// the budgeted CG (MGPCG, McAdams et al. 2010; cut-cell levels after Weber et al. 2015).
//
// Level 0 is the caller's CutCellPoisson, whatever it contains (collider fractions, Dirichlet
// open sides, free-surface terms): the hierarchy only reads its couplings and diagonal. Each
// coarser level halves the resolution (multigrid_coarsening.h) and is again a CutCellPoisson,
// applied and smoothed by the same code (multigrid_smoother.h); transfers are renormalized
// trilinear and its transpose (multigrid_transfer.h). Nothing but per-face couplings, diagonals,
// prolongation scales and work vectors is stored.
//
// The preconditioner z = M r is one V-cycle from zero: pre-smoothing, residual, restriction,
// recursion, prolongation, post-smoothing with the adjoint sweep order, and a fixed number of
// symmetric sweeps on the coarsest level. M is a fixed linear, symmetric, positive operator, as
// preconditioned CG needs. Floating (pure Neumann) regions of a coarse level get their right-hand
// side and their correction projected to zero mean, so every coarse solve is compatible and the
// constant null vector never enters a correction; level 0's filtering is the CG's.
//
// Cost of a cycle: 2 * sweeps smoothing passes and one residual per level, each a pass over the
// level's arrays, plus transfers; the levels shrink by 8, so about 8/7 of level 0's cost.
//
// Precision: the levels are built in double (coarsening sums many small fractions) and the
// V-cycle runs on single-precision copies of them, with single-precision vectors, as McAdams et
// al. 2010 do: every pass is bound by memory bandwidth, and floats halve the bytes. The CG around
// it stays in double (residuals, search directions, the solution), so the accuracy the CG reaches
// is unchanged; the preconditioner is a symmetric operator up to float round-off (~1e-7 of its
// output), which PCG tolerates (its search directions only need to be good, not exact).
// Measured on BM_PressureSolve (docs/benchmarks.md): same iteration counts as the double V-cycle.
#pragma once

#include <array>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/pressure/multigrid_coarsening.h"
#include "fluid/pressure/multigrid_smoother.h"
#include "fluid/pressure/multigrid_transfer.h"

namespace vp {

enum class MultigridCoarsening {
  CutCell,  // coarse face fractions from the fine ones: the thesis' method
  Voxel,    // coarse cells from voxel labels with full couplings: McAdams et al. 2010, baseline
};

struct MultigridSettings {
  MultigridCoarsening coarsening = MultigridCoarsening::CutCell;
  PoissonSmoother smoother = PoissonSmoother::RedBlackGaussSeidel;
  int sweeps = 2;  // smoothing sweeps before and after the coarse correction, per level
  // 6/7 minimizes the largest high-frequency amplification of Jacobi for the 7-point Laplacian.
  double jacobiWeight = 6.0 / 7.0;
  int coarsestSize = 4;      // stop coarsening before any grid dimension falls below this
  int coarsestSweeps = 24;   // sweeps, then as many adjoint sweeps, on the coarsest level
  // Extra Gauss-Seidel sweeps on cells near cut faces (findBoundaryCells), before and after the
  // coarse correction: without enough of them the iteration count grows with resolution on thin
  // solids, and each costs little, the lists being short (docs/choices.md, Pressure solve).
  int boundarySweeps = 16;
};

struct PoissonMultigrid {
  MultigridSettings settings;
  TransferSides sides;
  std::vector<CutCellPoisson> coarse;                 // levels 1 .. L-1, built in double
  Array<PoissonCoefficients<float>> single;     // levels 0 .. L-1: what the V-cycle applies
  Array<uint8_t> coarseFloating;                // per coarse level: any floating region
  std::vector<Array<float>> prolongScale;       // levels 0 .. L-2 (multigrid_transfer.h)
  std::vector<BoundaryCellLists> boundaryCells;       // per level (multigrid_smoother.h)
  std::vector<Array<float>> x, b, r;            // per level; level 0: the caller's r and z
  Array<float> restrictScratch;
  CoarseningScratch coarseningScratch;
  std::vector<ChangedRows> changed;  // per coarse level: rows changed since the last update
  Array<uint8_t> boundaryScratch;
  BoundarySweepValues boundaryValues;  // the boundary sweeps' values, one level at a time

  int levelCount() const { return 1 + static_cast<int>(coarse.size()); }
};

// `sides`: the domain's Open sides are Dirichlet for the transfers' ghosts and for the Voxel
// coarsening's coarse faces. Rebuild whenever the fine operator changes.
Status buildPoissonMultigrid(TaskSystem& tasks, const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides,
                             const MultigridSettings& settings, PoissonMultigrid* multigrid);

// What buildPoissonMultigrid checks of the settings and of the fine grid's size.
Status checkPoissonMultigrid(const MacGridSpec& fineGrid, const MultigridSettings& settings);

// buildPoissonMultigrid as passes (core/slab_passes.h; settings checked), per
// coarse level: its coarsening (multigrid_coarsening.h) and prolongation scales in slabs of
// rows; then per level the single-precision copy in slabs of values (of rows in an update) and
// the boundary cells (multigrid_smoother.h). Nothing of `fine` is read before the first pass
// runs, so fine may be built by the passes before them; fine and multigrid must outlive the
// passes.
// An update: with `fineChanged`, the rows of fine changed since the multigrid was last built
// from it (appendBuildCutCellPoisson raises them, changed_rows.h), the cut-cell levels are
// brought up to date where those rows reach (each level's own flags carry it to the next),
// and so are the single-precision copies, prolongation scales and boundary cells of the
// levels whose rows changed; the result is bit for bit that of a rebuild. Every level is
// rebuilt when the flags say all, the settings or sides differ from the last build's, or the
// coarsening is Voxel. The flags are cleared once every level is up to date.
void appendBuildPoissonMultigrid(const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides,
                                 const MultigridSettings& settings, PoissonMultigrid* multigrid, SlabPasses* passes,
                                 ChangedRows* fineChanged = nullptr);

// z = M r (one V-cycle); r and z have fine.cellCount entries and must not alias.
void applyPoissonMultigrid(TaskSystem& tasks, const CutCellPoisson& fine, PoissonMultigrid& multigrid,
                           const double* r, double* z);

}  // namespace vp

// Coarse levels of the pressure multigrid, each one a CutCellPoisson (couplings + diagonal on a
// grid of half the resolution), so every level is applied, smoothed and filtered by the same code.
//
// Cell (I, J, K) of the coarse grid covers the fine cells (2I .. 2I+1, 2J .. 2J+1, 2K .. 2K+1)
// that exist (odd fine counts: the last coarse cell has one child along that axis); coarse
// counts are ceil(n / 2), h doubles, the origin stays.
//
// Scaling. The fine operator is the finite-volume flux balance divided by h:
// (L p)_c = sum_f A_f (p_c - p_nb) (cut_cell_poisson.h). The multigrid restricts residuals with
// R = P^T for a prolongation P that reproduces constants (multigrid_transfer.h), so a coarse
// right-hand side is (in the interior) the sum of its 8 children's, i.e. the coarse cell's
// integrated source divided by h = (2h) / 2. The consistent finite-volume operator at spacing
// 2h in those units is 2 sum_F A_F (p_C - p_NB) with A_F the mean open fraction of the 4 fine
// columns under coarse face F, so
//     coarse coupling = (sum over the 4 fine columns of their open fraction) / 2,
//     coarse Dirichlet part = (sum of the children's Dirichlet parts) / 2,
// a column's open fraction being that of the fine face under F in series with half of each
// fine face behind it inside the two coarse cells (so a thin solid inside a coarse cell closes
// the column; multigrid_coarsening.cpp), and the Dirichlet part of a cell its diagonal minus the
// couplings of its faces (open domain sides). A column of three equal fractions keeps that
// fraction, so smooth geometry coarsens as by plain averaging. The coarse operator is the fine
// one at 2h with these fractions, i.e. about half the Galerkin product of piecewise-constant
// transfers, whose factor 2 overshoot is the known defect of that product.
// The free surface is the exception: its Dirichlet part is not summed but placed again by the
// fine level's ghost-fluid rule at the coarse spacing, from the children's mean level set
// (multigrid_coarsening.cpp says why).
//
// Voxel coarsening (McAdams et al. 2010, the baseline): a coarse cell is fluid when any child is,
// every coupling between two coarse fluid cells is that of a fully open face (2 in the units
// above), and a coarse cell on an Open domain side gets a fully open Dirichlet face there.
// There are no Dirichlet cells inside the domain until liquids exist; free-surface air cells
// would coarsen as solids here (a known weakness of this baseline, not of the cut-cell path).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/changed_rows.h"
#include "fluid/pressure/cut_cell_poisson.h"

namespace vp {

// The coarse grid spec of `fine` (ceil halves, h doubled, same origin).
MacGridSpec coarseGridSpec(const MacGridSpec& fine);

Status coarsenCutCell(TaskSystem& tasks, const CutCellPoisson& fine, CutCellPoisson* coarse);

Status coarsenVoxel(TaskSystem& tasks, const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides,
                    CutCellPoisson* coarse);

// Per coarse cell, between the passes of one coarsening (kept by the caller so a rebuild every
// step does not reallocate; one level at a time).
struct CoarseningScratch {
  Array<double> dirichlet;
  Array<uint8_t> fluid;
  Array<uint8_t> recompute;  // per coarse row, in an update: whether it is recomputed
};

// The coarsenings as passes (core/slab_passes.h), each in slabs of coarse rows
// (cut-cell: the faces per axis, the free surface's level set then its terms, the Dirichlet
// parts; voxel: the labels, the couplings cleared, the couplings and Dirichlet parts), then
// the diagonal and labelFluidRegions' and computeRowSpans' passes. Nothing of `fine` is read
// before the first pass runs, so the passes before them may build it. fine, coarse and
// scratch must outlive the passes.
//
// Updates (cut-cell only): given the rows of `fine` raised since `coarse` was last built from
// it (fineChanged) and coarse's own flags (coarseChanged), the cut-cell coarsening recomputes
// only the coarse rows those fine rows reach (and those raised in coarseChanged), except the
// level set and free-surface terms, which it recomputes everywhere, and raises in
// coarseChanged the rows whose values changed (changed_rows.h). The result is bit for bit that
// of a rebuild. Without flags (either null), when fineChanged or coarseChanged says all, or
// when coarse has another shape, it rebuilds everything and raises all of coarseChanged. The
// caller clears the flags once every level is up to date.
void appendCoarsenCutCell(const CutCellPoisson& fine, CutCellPoisson* coarse, CoarseningScratch* scratch,
                          SlabPasses* passes, const ChangedRows* fineChanged = nullptr,
                          ChangedRows* coarseChanged = nullptr);
void appendCoarsenVoxel(const CutCellPoisson& fine, const std::array<DomainSide, 6>& sides, CutCellPoisson* coarse,
                        CoarseningScratch* scratch, SlabPasses* passes);

}  // namespace vp

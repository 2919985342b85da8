// The finite-volume pressure operator of a cut-cell MAC grid (Batty et al. 2007; Ng, Min,
// Gibou 2009), defined by the face open fractions A_f and never stored as a matrix.
//
// For a fluid cell c with faces f and neighbours nb across them:
//     (L p)_c = sum_f A_f (p_c - p_nb)
// * interior face, A_f > 0: couples c and nb (nb is then fluid too, it shares the open face);
// * A_f = 0 (fully covered by a collider) or a domain Wall face: no term (Neumann);
// * domain Open face: Dirichlet ghost p_nb = 0, so A_f goes to the diagonal only.
// A cell is fluid when at least one of its faces is open; other cells (fully inside solids)
// have no row: p = 0 there and the filter keeps them 0.
//
// Scaling: the physical equation is (dt / (rho h^2)) L p = -(1/h) sum_f +-(...). L is kept
// unscaled (entries in [0, 6], independent of dt, rho, h) and the factor goes to the right-hand
// side, b = -(rho h / dt) * netOutflow, so p is the physical pressure (warm starts stay valid
// when dt changes) and the MIC(0) factors depend on the fractions only.
//
// Null space: a connected fluid region with no Dirichlet face ("floating", e.g. a closed
// box) has L 1 = 0 on it. filterCutCellPoisson() removes the region's mean, which makes the
// filtered CG (Baraff-Witkin style, see conjugate_gradient.h) solve the compatible part; the
// pressure there is defined up to a constant and comes out with zero mean.
//
// Free surface (liquids; free_surface.h): with a level set, only liquid cells (phi < 0 with an
// open face) have rows; air cells have p = 0 and no row. A face between a liquid cell c and
// an air cell drops its coupling and adds A_f / theta to c's diagonal (symmetric ghost fluid,
// Gibou 2002). So the meaning of the struct is unchanged: couplings between two row cells,
// diagonal = sum of the open couplings + Dirichlet terms (open domain sides, free surface),
// and code that reads only the struct (MIC(0), multigrid) picks the free surface up. A
// liquid region touching air is not floating (the surface is Dirichlet).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/allocator.h"
#include "core/slab_passes.h"
#include "core/status.h"
#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/changed_rows.h"
#include "fluid/solids/face_fraction_field.h"
#include "gpu_kernels/net_outflow_kernels.h"
#include "gpu_kernels/pressure_update_kernels.h"

namespace vp {

// The coefficients of the operator on a grid, in double (CutCellPoisson) or in single precision
// (the multigrid's V-cycle, poisson_multigrid.h).
template <class T>
struct PoissonCoefficients {
  MacGridSpec grid;
  // Per face (face layout): A_f for faces between two cells of the grid, 0 for boundary faces
  // (their Dirichlet part is in the diagonal) and closed faces.
  Array<T> coupling[3];
  // Per cell: sum of A_f over the cell's open faces, Dirichlet faces included; 0 off fluid.
  Array<T> diagonal;
  // Per grid row (j + ny k): [begin, end) of the i of its fluid cells, first to last (begin ==
  // end when the row has none). Kernels skip the rest of the row (poisson_rows.h); empty means
  // "every row spans all its cells".
  Array<int32_t> rowSpan;
};

struct CutCellPoisson : PoissonCoefficients<double> {
  // Per cell: connected fluid region id, -1 for cells that are not fluid.
  Array<int32_t> region;
  Array<uint8_t> regionFloating;  // per region: 1 when it has no Dirichlet face
  Array<int64_t> regionCellCount;
  int64_t fluidCellCount = 0;
  // Per cell, with a free surface only (else empty): 1 for an air cell (level set >= 0) that is
  // not wholly inside a solid. The voxel-label multigrid baseline makes coarse cells over air
  // Dirichlet (multigrid_coarsening.h); the operator itself does not need it.
  Array<uint8_t> air;
  // With a free surface only (else empty), so that the multigrid's coarse levels can place the
  // surface with the same ghost-fluid rule at their own spacing (multigrid_coarsening.h)
  // instead of summing the fine levels' terms, which puts it at the wrong depth:
  // per cell the level set, per face the open fraction a coupling would have without the free
  // surface (interior faces; the coupling's units), per cell the free-surface part of the diagonal.
  Array<double> liquidPhi;
  Array<double> openFraction[3];
  Array<double> surfaceDirichlet;

  bool isFluid(size_t cell) const { return region[cell] >= 0; }
};

// Open fractions below kMinOpenFraction count as closed (gpu_kernels/pressure_update_kernels.h
// says why).
using kernels::kMinOpenFraction;
using kernels::openedFraction;

// The fraction the operator, the right-hand side and the velocity update use for a face: the
// collider open fraction, forced to 0 on domain Wall faces and below kMinOpenFraction.
// Inline: the operator's build, the net outflow and the velocity extrapolation's marks call it
// per face.
inline double effectiveOpenFraction(const MacGrid& grid, const FaceFractionField& fractions, int axis, int i, int j,
                                    int k) {
  if (grid.isWallFace(axis, i, j, k)) return 0.0;
  return openedFraction(fractions.open[axis][grid.faceIndex(axis, i, j, k)]);
}

// Builds the couplings, diagonal and fluid regions. The fractions must belong to grid.spec.
// liquidPhi: nullptr for smoke (every cell with an open face is fluid), else the liquid level
// set (cellCount values, free_surface.h) for the free-surface operator.
Status buildCutCellPoisson(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                           CutCellPoisson* op, const double* liquidPhi = nullptr);

// Sizes op's arrays for `grid`: the free-surface arrays (liquidPhi, surfaceDirichlet,
// openFraction) only when `freeSurface`, air only when `air`, else empties them. Values are
// left to the builder's passes, which write every one.
void sizeCutCellPoisson(const MacGridSpec& grid, bool freeSurface, bool air, CutCellPoisson* op);

// What buildCutCellPoisson checks of its inputs (the fractions' grid and array sizes).
Status checkCutCellPoissonInputs(const MacGrid& grid, const FaceFractionField& fractions);

// buildCutCellPoisson as passes (inputs checked; they and op must outlive the passes): the
// couplings in slabs of face rows per axis, the diagonal in slabs of grid rows (kernel bodies
// in gpu_kernels/poisson_build_kernels.h), then
// labelFluidRegions' and computeRowSpans' passes. `changed` (optional): the rows whose values
// change are raised, all of them when op had another shape (changed_rows.h); the multigrid
// update that consumes them clears them.
void appendBuildCutCellPoisson(const MacGrid& grid, const FaceFractionField& fractions, CutCellPoisson* op,
                               const double* liquidPhi, SlabPasses* passes, ChangedRows* changed = nullptr);

// Per cell: diagonal minus the couplings of the cell's faces (open domain sides, free-surface
// faces); 0 on non-fluid cells and where the difference is round-off (below 1e-12 of the
// diagonal).
double dirichletPart(const CutCellPoisson& op, int64_t cell);
// The same for every cell of grid row `row` (j + ny k): parts[i], i = 0 .. nx - 1.
void dirichletPartsOfRow(const CutCellPoisson& op, int64_t row, double* parts);

// Fills op->region, regionFloating, regionCellCount and fluidCellCount from the couplings and
// diagonal: a region is a set of fluid cells (diagonal > 0) connected through positive
// couplings, numbered in the order of their first cell; floating when none of its cells has a
// Dirichlet part. Every builder of a CutCellPoisson calls it.
// Two serial scans in cell order (a union-find that links each cell to its coupled -x, -y, -z
// neighbours, the smaller index becoming the root; then the numbering), so that they can stop
// after any cell and resume: connectivity is a property of the whole grid, but a scan in a
// fixed order gives the same labels however it is cut.
void labelFluidRegions(CutCellPoisson* op);
void appendLabelFluidRegions(CutCellPoisson* op, SlabPasses* passes);

// Fills op->rowSpan from op->diagonal (a cell is fluid when its diagonal is positive). Every
// builder of a CutCellPoisson calls it last.
void computeRowSpans(TaskSystem& tasks, CutCellPoisson* op);
void appendComputeRowSpans(CutCellPoisson* op, SlabPasses* passes);

// out = L p over all cells (0 on non-fluid cells). p and out have cellCount entries.
void applyCutCellPoisson(TaskSystem& tasks, const CutCellPoisson& op, const double* p, double* out);

// In place: zero on non-fluid cells, zero mean on every floating region (T: double or float).
// The CG filters twice per iteration, so without floating regions (the common case: any open
// side or free surface) it runs in parallel; the region means are summed serially.
template <class T>
void filterCutCellPoisson(TaskSystem& tasks, const CutCellPoisson& op, T* values);

// Per cell: the net outflow sum_f +-(A_f u_f + (1 - A_f) u_solid,f) through the cell's faces
// (velocity times area / h^2; + on the high face of each axis). The discrete divergence is
// netOutflow / h. 0 on non-fluid cells.
// A domain Wall face stops the fluid (A_f u_f = 0) but not a collider that reaches through
// it: its covered part carries the collider's velocity like any other face. A body moving
// into the wall then leaves its cell through that face instead of squeezing the cell's fluid
// out of the remaining gaps (a floating ball 4 cm into a wall met the pressure of a piston,
// and the explicit coupling threw it at 20+ m/s).
void computeNetOutflow(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                       const CutCellPoisson& op, double* outflow);
// The kernel body's view of the grid's velocity and the fractions (net_outflow_kernels.h).
kernels::NetOutflowFields netOutflowFields(const MacGrid& grid, const FaceFractionField& fractions);
// The same on cells [begin, end) only, on the calling thread.
void computeNetOutflowCells(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                            int64_t begin, int64_t end, double* outflow);

}  // namespace vp

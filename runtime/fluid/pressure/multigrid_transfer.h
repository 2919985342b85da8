// Grid transfers of the pressure multigrid: cell-centred trilinear prolongation, renormalized
// over the coarse cells that are fluid, and its exact transpose as restriction.
//
// Fine cell i (per axis) lies between its parent I = i / 2 (weight 3/4) and the coarse cell on
// the side of i within the parent, I + 1 for odd i, I - 1 for even i (weight 1/4); the weight of
// a coarse cell is the product over the axes. Coarse cells outside the grid or not fluid are
// dropped and the remaining weights divided by their sum S_i, so the prolongation reproduces
// constants up to solids and walls (a Neumann-like extrapolation; plain trilinear would pull the
// correction to 0 next to every solid, which McAdams et al. patch with extra boundary smoothing):
//     (P x)_i = (1 / S_i) sum_I w_iI x_I          (0 on non-fluid fine cells)
//     R = P^T:  (R r)_I = sum_i w_iI r_i / S_i     (0 on non-fluid coarse cells)
// A ghost coarse cell behind an Open domain side (Dirichlet p = 0 on the domain face) is not
// dropped but mirrored, x_ghost = -x_parent, so corrections vanish at the open face instead of
// being extrapolated flat through it.
// R = P^T exactly is what keeps the V-cycle symmetric (multigrid_coarsening.h derives the coarse
// operator's scaling for this R).
// The per-value kernel bodies are in gpu_kernels/include/gpu_kernels/transfer_kernels.h; the
// functions below run them a row at a time.
#pragma once

#include <vector>

#include "core/allocator.h"
#include "core/task_system.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "gpu_kernels/transfer_kernels.h"

namespace vp {

// Which domain sides are Open (Dirichlet), in MacGrid::sides order.
using TransferSides = kernels::TransferSides;

// Per fine cell: 1 / S_i, 0 on non-fluid fine cells and where no coarse neighbour is fluid.
void computeProlongationScale(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                              const TransferSides& sides, Array<double>* scale);
// The same as passes (core/slab_passes.h), in slabs of fine rows; nothing is read
// before the first runs. The arguments must outlive the passes.
void appendComputeProlongationScale(const CutCellPoisson& fine, const CutCellPoisson& coarse,
                                    const TransferSides& sides, Array<double>* scale, SlabPasses* passes);

// The same for the nx cells of fine grid row `row` (j + ny k) alone, into scale[0 .. nx). It
// reads the fine row's diagonal and the coarse diagonal in coarse rows j / 2 - 1 .. j / 2 + 1
// and k / 2 - 1 .. k / 2 + 1.
void prolongationScaleRow(const CutCellPoisson& fine, const CutCellPoisson& coarse, const TransferSides& sides,
                          int64_t row, double* scale);

// fineX += P coarseX.
// T: double or float (the V-cycle's precision, poisson_multigrid.h).
template <class T>
void prolongateAdd(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                   const TransferSides& sides, const T* scale, const T* coarseX, T* fineX);

// The residual r = b - A x of a level (op: its coefficients in the V-cycle's precision), which
// the restriction computes a row at a time where it reads it: the V-cycle never stores it.
template <class T>
struct LevelResidual {
  const PoissonCoefficients<T>* op;
  const T* b;
  const T* x;
};

// coarseB = P^T (b - A x). `scratch` holds the partial sums (resized, so reuse it across calls).
template <class T>
void restrictResidual(TaskSystem& tasks, const CutCellPoisson& fine, const CutCellPoisson& coarse,
                      const TransferSides& sides, const T* scale, const LevelResidual<T>& residual, T* coarseB,
                      Array<T>* scratch);

}  // namespace vp

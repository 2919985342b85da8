// Smoothers and residual of one pressure multigrid level (a CutCellPoisson), parallel over grid
// rows through parallel_for.
//
// Red-black Gauss-Seidel: cells with (i + j + k) even are red, the others black; the 7-point
// operator couples only cells of different colours, so each half-sweep updates its colour in any
// order (in parallel, and bitwise independent of the worker count). One sweep is red then black;
// its adjoint (in the A inner product) is black then red, which the V-cycle uses after the
// coarse correction so that the whole cycle is a symmetric operator.
//
// Damped Jacobi: x += w D^-1 (b - A x), symmetric by itself.
//
// A Jacobi sweep is one contiguous (vectorizable) pass, a fused red-black sweep one strided pass
// plus a second phase on two planes per slab: Jacobi's cheaper sweeps and its extra iterations
// come out level in time (BM_PressureSolve, cutcell_mgpcg against cutcell_mgpcg_jacobi; figures
// in docs/benchmarks.md), so Gauss-Seidel stays the default for the lower iteration count
// (fewer CG dot products and operator applications).
//
// Non-fluid cells (diagonal 0) are never written: they hold 0 and keep it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/task_system.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "gpu_kernels/smoother_kernels.h"

namespace vp {

enum class PoissonSmoother { RedBlackGaussSeidel, DampedJacobi };

// One red-black sweep (red then black; black then red when `reverse`). `fromZero`: the sweep
// starts from x = 0 whatever x holds (every cell is written, non-fluid ones with 0).
// T is double or float (the V-cycle runs in single precision, poisson_multigrid.h).
template <class T>
void smoothRedBlack(TaskSystem& tasks, const PoissonCoefficients<T>& op, const T* b, T* x, bool reverse,
                    bool fromZero = false);

// `sweeps` damped Jacobi sweeps; `scratch` has the level's cell count; `fromZero` as for
// smoothRedBlack.
template <class T>
void smoothJacobi(TaskSystem& tasks, const PoissonCoefficients<T>& op, const T* b, T* x, T* scratch, double weight,
                  int sweeps, bool fromZero = false);

// Boundary smoothing (McAdams et al. 2010): Gauss-Seidel restricted to the listed cells, split
// by colour (red list then black list; black then red when `reverse`), so it parallelizes like
// the full sweep and its reverse is its adjoint.
// A listed cell carries its own coefficients (gpu_kernels/smoother_kernels.h).
using BoundaryCell = kernels::BoundaryCell;

// A level's listed cells and what each of their faces reads during the sweeps. The sweeps of
// one smoothing change only listed cells, so a face reading an unlisted cell reads a constant:
// the sweeps run on compact copies (BoundarySweepValues) instead of reaching across the grid
// for every face of every listed cell in every sweep.
struct BoundaryCellLists {
  std::array<Array<BoundaryCell>, 2> byColour;  // red, black
  // Per listed cell (entry e: the red list's cells, then the black's) and face f, where in
  // BoundarySweepValues::values the face's value is: the entry of the listed cell it reads
  // (itself when the coupling is 0), else count() + 6 e + f, a constant.
  Array<int32_t> reads;
  int64_t count() const { return static_cast<int64_t>(byColour[0].size() + byColour[1].size()); }
};

// What one smoothing's boundary sweeps work on: the listed cells' x, then the constants.
struct BoundarySweepValues {
  Array<float> values;
  Array<float> rhs;  // b of the listed cells
};

// `sweeps` boundary sweeps of x: the same values, bit for bit, as that many sweeps reading and
// writing x in place.
void smoothBoundaryCells(TaskSystem& tasks, const PoissonCoefficients<float>& op, const BoundaryCellLists& cells,
                         const float* b, float* x, bool reverse, int sweeps, BoundarySweepValues* scratch);

// The fluid cells within one face step of a cut cell, split by colour: red cells in
// byColour[0], black in byColour[1], each in cell order. A cell is cut when a face inside the
// grid has a coupling below the level's full value `fullCoupling` (solids, slivers) or when it
// has a Dirichlet part away from the domain sides (free surface). The multigrid's convergence
// degrades with resolution without these sweeps: sliver cells (open fractions near 0) are
// poorly represented by the coarse levels, and their number grows with the surface.
void findBoundaryCells(TaskSystem& tasks, const CutCellPoisson& op, double fullCoupling,
                       BoundaryCellLists* cells);
// The same as passes (core/slab_passes.h): the cut flags (into `cut`, one per
// cell) in slabs of rows, then the lists in rows taken in order, then the faces' reads.
// Nothing is read before the first pass runs; the arguments must outlive the passes.
void appendFindBoundaryCells(const CutCellPoisson& op, double fullCoupling, BoundaryCellLists* cells,
                             Array<uint8_t>* cut, SlabPasses* passes);

// r = b - A x on fluid cells, 0 elsewhere.
template <class T>
void computeResidual(TaskSystem& tasks, const PoissonCoefficients<T>& op, const T* b, const T* x, T* r);

}  // namespace vp

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
// Non-fluid cells (diagonal 0) are never written: they hold 0 and keep it.
#pragma once

#include "core/task_system.h"
#include "fluid/cut_cell_poisson.h"

namespace vp {

enum class MultigridSmoother { RedBlackGaussSeidel, DampedJacobi };

// One red-black sweep (red then black; black then red when `reverse`).
void smoothRedBlack(TaskSystem& tasks, const CutCellPoisson& op, const double* b, double* x, bool reverse);

// One damped Jacobi sweep; `scratch` has the level's cell count.
void smoothJacobi(TaskSystem& tasks, const CutCellPoisson& op, const double* b, double* x, double* scratch,
                  double weight);

// r = b - A x on fluid cells, 0 elsewhere.
void computeResidual(TaskSystem& tasks, const CutCellPoisson& op, const double* b, const double* x, double* r);

}  // namespace vp

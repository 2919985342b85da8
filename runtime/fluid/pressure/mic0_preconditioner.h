// MIC(0): modified incomplete Cholesky with zero fill-in for the 7-point cut-cell operator
// (Bridson, "Fluid Simulation for Computer Graphics", ch. 5), built from the operator's face
// couplings and diagonal: L L^T ~ A with L's sparsity that of A's lower triangle, and the
// dropped fill-in moved to the diagonal (scaled by `tuning`), so row sums are (nearly) kept.
//
// Applied by a forward then a backward triangular solve in lexicographic cell order. Both
// solves are serial: each cell needs its already-solved -x, -y, -z (resp. +x, +y, +z)
// neighbours, a dependency chain through the whole grid. A parallel preconditioner (red-black
// smoothing or the cut-cell multigrid) is issue 7.
#pragma once

#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "fluid/pressure/cut_cell_poisson.h"

namespace vp {

struct Mic0Settings {
  double tuning = 0.97;  // fraction of the dropped fill-in moved to the diagonal (1 = full MIC)
  double safety = 0.25;  // a pivot below safety * diagonal falls back to the diagonal (plain IC)
};

struct Mic0Preconditioner {
  // Per cell: 1 / sqrt(pivot) of the factor's diagonal; 0 on non-fluid cells.
  Array<double> inverseSqrtPivot;
};

Status buildMic0Preconditioner(const CutCellPoisson& op, const Mic0Settings& settings,
                               Mic0Preconditioner* preconditioner);

// z = (L L^T)^-1 r over all cells; z may alias r. Non-fluid cells get 0.
void applyMic0Preconditioner(const CutCellPoisson& op, const Mic0Preconditioner& preconditioner,
                             const double* r, double* z);

}  // namespace vp

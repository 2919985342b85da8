// The views a CUDA device's pressure solve and projection (gpu_kernels/device_pressure_solver.h,
// device_projection.h) upload: the fine operator and its regions, every level of a built
// multigrid, and the grid's fractions, as host arrays that stay owned by the arguments (which
// must outlive the view).
#pragma once

#include "core/status.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/pressure/poisson_multigrid.h"
#include "gpu_kernels/device_pressure_solver.h"
#include "gpu_kernels/device_projection.h"

namespace vp {

// Fails, naming the setting, for a hierarchy the device does not run (the damped Jacobi
// smoother: the device sweeps red-black Gauss-Seidel only).
Status makePressureSolveView(const CutCellPoisson& fine, const PoissonMultigrid& multigrid,
                             gpu::PressureSolveView* view);

// The projection's: makePressureSolveView's and the grid's layout, spacing and fractions;
// liquidPhi as for projectVelocity (null for smoke).
Status makeProjectionView(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& fine,
                          const PoissonMultigrid& multigrid, const double* liquidPhi, gpu::ProjectionView* view);

}  // namespace vp

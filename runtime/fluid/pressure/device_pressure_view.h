// The view a CUDA device's pressure solve (gpu_kernels/device_pressure_solver.h) uploads: the
// fine operator and its regions, and every level of a built multigrid, as host arrays that
// stay owned by `fine` and `multigrid` (which must outlive the view).
#pragma once

#include "core/status.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/pressure/poisson_multigrid.h"
#include "gpu_kernels/device_pressure_solver.h"

namespace vp {

// Fails, naming the setting, for a hierarchy the device does not run (the damped Jacobi
// smoother: the device sweeps red-black Gauss-Seidel only).
Status makePressureSolveView(const CutCellPoisson& fine, const PoissonMultigrid& multigrid,
                             gpu::PressureSolveView* view);

}  // namespace vp

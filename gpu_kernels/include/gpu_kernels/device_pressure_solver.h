// The cut-cell pressure solve resident on a CUDA device: the CPU's multigrid-preconditioned
// CG (runtime/fluid/pressure/poisson_multigrid.h, linalg/conjugate_gradient.h) with the same
// mathematics. The fine operator and the CG stay in double; the V-cycle runs on the levels'
// single-precision copies, as on the CPU. The hierarchy is built on the CPU and uploaded here
// (runtime/fluid/pressure/device_pressure_view.h takes its view); the cycle is one CUDA graph,
// recorded once, so its few hundred small launches (coarse levels, boundary sweeps) cost one.
// Only declared where the CUDA path is compiled (VP_HAVE_CUDA); failures come back as false
// with the CUDA error text.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpu_kernels/poisson_kernels.h"
#include "gpu_kernels/smoother_kernels.h"
#include "gpu_kernels/transfer_kernels.h"

namespace vp::gpu {

// A level's connected fluid regions, for the filter that zeroes non-fluid cells and removes
// the mean of each floating (pure Neumann) region (filterCutCellPoisson).
struct RegionView {
  const int32_t* region = nullptr;  // per cell, -1: not fluid
  const uint8_t* floating = nullptr;
  const int64_t* cellCount = nullptr;
  int64_t count = 0;
  bool anyFloating = false;
};

// One multigrid level as host arrays.
struct MultigridLevelView {
  kernels::PoissonStencil<float> op{};   // single-precision couplings and diagonal (span unused)
  const float* prolongScale = nullptr;   // toward the next coarser level; null on the coarsest
  RegionView regions;                    // read on coarse levels with a floating region
  const kernels::BoundaryCell* boundary[2] = {nullptr, nullptr};  // red, black lists
  int64_t boundaryCount[2] = {0, 0};
  const int32_t* boundaryReads = nullptr;  // 6 per entry, the red entries first
};

struct PressureSolveView {
  kernels::PoissonStencil<double> fine{};  // the CG's operator
  RegionView fineRegions;                  // the CG's filter
  std::vector<MultigridLevelView> levels;  // level 0 is the fine grid in single precision
  kernels::TransferSides sides;
  int sweeps = 0, coarsestSweeps = 0, boundarySweeps = 0;
};

struct DevicePressureResult {
  int iterations = 0;
  double relativeResidual = 0.0;
  bool converged = false;
  double ms = 0.0;  // the solve on the device, b resident to x resident (device events)
};

class DevicePressureSolver {
 public:
  static std::unique_ptr<DevicePressureSolver> create(const PressureSolveView& view, std::string* error);
  ~DevicePressureSolver();
  DevicePressureSolver(const DevicePressureSolver&) = delete;
  DevicePressureSolver& operator=(const DevicePressureSolver&) = delete;

  // z = M r (one V-cycle) for host vectors of the fine grid's cell count.
  bool vcycle(const double* r, double* z, std::string* error);
  // MGPCG from the guess in x (the CPU's warm start) until |r| <= tolerance |filtered b| or
  // maxIterations, host vectors.
  bool solve(const double* b, double* x, double tolerance, int maxIterations, DevicePressureResult* result,
             std::string* error);
  // The same on the resident vectors: b in rhs(), the guess and the solution in solution()
  // (device pointers of the fine grid's cell count, on the legacy default stream's side:
  // work queued there before the call is done before the solve reads them).
  bool solveResident(double tolerance, int maxIterations, DevicePressureResult* result, std::string* error);
  double* rhs() const;
  double* solution() const;
  // Device milliseconds per V-cycle and per fine operator application, resident vectors.
  bool timeVcycle(int repeats, double* msPerCycle, double* msPerApply, std::string* error);

 private:
  struct Impl;
  explicit DevicePressureSolver(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

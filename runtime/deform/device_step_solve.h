// A deformable's implicit-step solve on a CUDA device (the world's device choice, vpWorldDef.device):
// the step matrix goes to the device as BIN-BCSR (the pattern once, the values whenever an
// assembly changed them), the node constraints and the right-hand side with every solve, and
// the filtered block-Jacobi CG runs there fused (gpu_kernels/device_block_system.h). It stops
// at the frame plan's deadlines as the CPU's CG does (linalg/conjugate_gradient.h), looking at
// the clock every DeviceBlockSystem::kStopCheckInterval iterations. Block-Jacobi is the
// device's preconditioner whatever the desc chose: the multigrids run on the CPU only.
#pragma once

#include <memory>

#include "core/allocator.h"
#include "core/budget_clock.h"
#include "core/status.h"
#include "deform/node_constraints.h"
#include "linalg/bin_bcsr_matrix.h"
#include "linalg/block_sparse_matrix.h"
#include "linalg/conjugate_gradient.h"

namespace vp {

namespace gpu {
class DeviceBlockSystem;
}

class DeviceStepSolve {
 public:
  // Fails (Unsupported without CUDA or a device, OutOfMemory on the device) with the reason in
  // lastError(); `matrix` must have its final pattern.
  static Status create(const BlockSparseMatrix<double>& matrix, std::unique_ptr<DeviceStepSolve>* out);
  ~DeviceStepSolve();

  // The assembly wrote new values into the matrix: the next solve uploads them.
  void matrixChanged() { valuesOnDevice_ = false; }
  // Solves A x = b from x as solveConjugateGradient does with an accuracy floor;
  // inverseDiagonals holds the block-Jacobi inverses, 9 per node. A CUDA failure is returned
  // (x is then unchanged) for the caller to solve on the CPU.
  Status solve(const BlockSparseMatrix<double>& matrix, const double* inverseDiagonals, const NodeConstraints& held,
               const double* b, double* x, const CgSettings& settings, const Deadline& deadline, double floorTolerance,
               const Deadline& floorDeadline, CgResult* out);

 private:
  DeviceStepSolve() = default;

  BinBcsrMatrix<double> bin_;
  Array<double> binnedInverse_;
  Array<double> result_;
  bool valuesOnDevice_ = false;
  std::unique_ptr<gpu::DeviceBlockSystem> device_;
};

}  // namespace vp

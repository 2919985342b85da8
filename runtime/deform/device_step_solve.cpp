#include "deform/device_step_solve.h"

#include <algorithm>
#include <string>

#include "core/status.h"
#include "gpu_kernels/device_block_system.h"
#include "gpu_kernels/device_query.h"

namespace vp {

namespace {

// The CPU CG's stop rule past the deadline (solveConjugateGradient with a floor).
struct StopRule {
  const Deadline* deadline;
  const Deadline* floorDeadline;
  double floorTolerance;

  static bool stop(void* context, int, double relativeResidual) {
    const StopRule& rule = *static_cast<const StopRule*>(context);
    return rule.deadline->expired() &&
           (relativeResidual <= rule.floorTolerance || rule.floorDeadline->expired());
  }
};

}  // namespace

Status DeviceStepSolve::create(const BlockSparseMatrix<double>& matrix, std::unique_ptr<DeviceStepSolve>* out) {
  if (gpu::cudaDeviceCount() == 0) return fail(Status::Unsupported, "no CUDA device is usable");
  std::unique_ptr<DeviceStepSolve> solve(new DeviceStepSolve);
  buildBinBcsr(matrix, &solve->bin_);
  // The first solve uploads the values with the assembly's block-Jacobi inverses: until then
  // the device holds zeros there rather than inverses computed a second time.
  solve->binnedInverse_.assign(solve->bin_.diagonal.size(), 0.0);
  gpu::HostBlockSystem host;
  host.matrix = solve->bin_.view();
  host.slots = solve->bin_.slots();
  host.inverseDiagonal = solve->binnedInverse_.data();
  std::string error;
  solve->device_ = gpu::DeviceBlockSystem::create(host, &error);
  if (!solve->device_) return fail(Status::OutOfMemory, "the deformable's solve on the CUDA device: %s", error.c_str());
  *out = std::move(solve);
  return Status::Ok;
}

Status DeviceStepSolve::solve(const BlockSparseMatrix<double>& matrix, const double* inverseDiagonals,
                              const NodeConstraints& held, const double* b, double* x, const CgSettings& settings,
                              const Deadline& deadline, double floorTolerance, const Deadline& floorDeadline,
                              CgResult* out) {
  std::string error;
  if (!valuesOnDevice_) {
    refreshBinBcsrValues(matrix, &bin_);
    binnedBlocks(inverseDiagonals, matrix.blockRows, &binnedInverse_);
    if (!device_->setValues(bin_.values.data(), bin_.diagonal.data(), binnedInverse_.data(), &error))
      return fail(Status::Internal, "uploading the deformable's step matrix to the CUDA device: %s", error.c_str());
    valuesOnDevice_ = true;
  }
  if (!device_->setConstraints(held.kind.data(), held.normal.data(), &error))
    return fail(Status::Internal, "uploading the deformable's constraints to the CUDA device: %s", error.c_str());
  StopRule rule{&deadline, &floorDeadline, floorTolerance};
  gpu::DeviceCgControl control;
  control.stop = &StopRule::stop;
  control.context = &rule;
  result_.assign(x, x + 3 * static_cast<size_t>(matrix.blockRows));
  gpu::DeviceCgResult r;
  if (!device_->solve(b, result_.data(), settings.relativeTolerance, settings.maxIterations, gpu::DeviceCgForm::Fused,
                      &r, &error, control))
    return fail(Status::Internal, "the deformable's solve on the CUDA device: %s", error.c_str());
  std::copy(result_.begin(), result_.end(), x);
  out->iterations = r.iterations;
  out->relativeResidual = r.relativeResidual;
  out->converged = r.converged;
  out->budgetCut = r.stoppedByCaller;
  return Status::Ok;
}

DeviceStepSolve::~DeviceStepSolve() = default;

}  // namespace vp

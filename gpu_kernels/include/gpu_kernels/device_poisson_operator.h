// The cut-cell pressure operator resident on a CUDA device, applied as an implicit 7-point
// stencil (the couplings and diagonal; no matrix is stored), one thread per cell through the
// kernel body the CPU's rows share (gpu_kernels/poisson_kernels.h). Only declared where the
// CUDA path is compiled (VP_HAVE_CUDA); failures come back as false with the CUDA error text.
#pragma once

#include <memory>
#include <string>

#include "gpu_kernels/poisson_kernels.h"

namespace vp::gpu {

class DevicePoissonOperator {
 public:
  // Copies the stencil's arrays (its span is not used: every cell gets a thread).
  static std::unique_ptr<DevicePoissonOperator> create(const kernels::PoissonStencil<double>& host, std::string* error);
  ~DevicePoissonOperator();
  DevicePoissonOperator(const DevicePoissonOperator&) = delete;
  DevicePoissonOperator& operator=(const DevicePoissonOperator&) = delete;

  // y = L x for host vectors of nx ny nz values.
  bool apply(const double* x, double* y, std::string* error);
  // `repeats` applications between resident vectors; device milliseconds per application.
  bool timeApply(int repeats, double* msPerApply, std::string* error);

 private:
  struct Impl;
  explicit DevicePoissonOperator(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

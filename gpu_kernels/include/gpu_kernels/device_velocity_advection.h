// A MAC grid's velocity resident on a CUDA device, advected there by itself: one thread per face
// through the kernel bodies the CPU's advection runs (gpu_kernels/advection_kernels.h:
// advectFace, maccormackFace), compiled without contraction (--fmad=false), so each face gets
// the CPU's bits (advectVelocity without a skip mask). Only declared where the CUDA path is
// compiled (VP_HAVE_CUDA); failures come back as false with the CUDA error text.
#pragma once

#include <memory>
#include <string>

#include "gpu_kernels/advection_kernels.h"

namespace vp::gpu {

class DeviceVelocityAdvection {
 public:
  // The grid's layout and velocity from a view of host arrays.
  static std::unique_ptr<DeviceVelocityAdvection> create(const kernels::MacVelocityView& host, std::string* error);
  ~DeviceVelocityAdvection();
  DeviceVelocityAdvection(const DeviceVelocityAdvection&) = delete;
  DeviceVelocityAdvection& operator=(const DeviceVelocityAdvection&) = delete;

  // Replaces the device's velocity by itself advected over dt (semi-Lagrangian, or MacCormack).
  bool advect(double dt, bool maccormack, std::string* error);
  // The device's velocity into host arrays of the view's face counts.
  bool download(double* const u[3], std::string* error);
  // Device milliseconds per advect(), over `repeats` (the velocity changes as it runs).
  bool timeAdvect(int repeats, double dt, bool maccormack, double* msPerAdvect, std::string* error);

 private:
  struct Impl;
  explicit DeviceVelocityAdvection(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

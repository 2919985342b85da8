// The pressure projection of a MAC velocity on a CUDA device (runtime/fluid/pressure/
// pressure_projection.h has the method): the right-hand side from the velocity's net outflow
// (gpu_kernels/net_outflow_kernels.h), the MGPCG solve (device_pressure_solver.h) warm-started
// from the caller's pressure, and the velocity update (gpu_kernels/pressure_update_kernels.h),
// each a thread per cell or face over the kernel bodies the CPU runs. The operator and its
// multigrid are built on the CPU (runtime/fluid/pressure/device_pressure_view.h). Only declared
// where the CUDA path is compiled (VP_HAVE_CUDA); failures come back as false with the CUDA
// error text.
#pragma once

#include <memory>
#include <string>

#include "gpu_kernels/device_pressure_solver.h"
#include "gpu_kernels/net_outflow_kernels.h"

namespace vp::gpu {

struct ProjectionView {
  // Host arrays: the faces' open fractions and solids' normal velocities, and the grid's
  // layout (the velocity pointers are not read: project() takes the velocity).
  kernels::NetOutflowFields fractions{};
  double h = 0.0;
  const double* liquidPhi = nullptr;  // per cell for a liquid, null for smoke
  PressureSolveView solve;            // the operator (fine.region: which cells are fluid)
};

class DeviceProjection {
 public:
  static std::unique_ptr<DeviceProjection> create(const ProjectionView& view, std::string* error);
  ~DeviceProjection();
  DeviceProjection(const DeviceProjection&) = delete;
  DeviceProjection& operator=(const DeviceProjection&) = delete;

  // Projects the host velocity u (three MAC arrays) in place over dt; `pressure` (per cell) is
  // the warm start on the way in (0 written on non-fluid cells, as the CPU does) and the
  // solution on the way out.
  bool project(double* const u[3], double* pressure, double dt, double density, double tolerance, int maxIterations,
               DevicePressureResult* result, std::string* error);

 private:
  struct Impl;
  explicit DeviceProjection(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

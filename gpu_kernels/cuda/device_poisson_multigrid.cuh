// The pressure multigrid's V-cycle resident on the device (device_pressure_solver.h has the
// contract): the levels' arrays, the region filters, and the cycle recorded as a CUDA graph.
#pragma once

#include <cuda_runtime.h>

#include <memory>
#include <string>
#include <vector>

#include "device_support.cuh"
#include "gpu_kernels/device_pressure_solver.h"

namespace vp::gpu {

// filterCutCellPoisson on the device: 0 on non-fluid cells, zero mean on floating regions (the
// region sums in double, as on the CPU, but added in the order the threads arrive).
class DeviceRegionFilter {
 public:
  bool upload(const RegionView& view, int64_t cells, std::string* error);
  void apply(float* values, cudaStream_t stream);
  void apply(double* values, cudaStream_t stream);

 private:
  template <class T>
  void run(T* values, cudaStream_t stream);
  int64_t cells_ = 0, regions_ = 0;
  bool anyFloating_ = false;
  DeviceArray<int32_t> region_;
  DeviceArray<uint8_t> floating_;
  DeviceArray<double> inverseCount_, sum_;
};

class DeviceMultigrid {
 public:
  DeviceMultigrid();
  ~DeviceMultigrid();
  DeviceMultigrid(const DeviceMultigrid&) = delete;
  DeviceMultigrid& operator=(const DeviceMultigrid&) = delete;

  bool upload(const PressureSolveView& view, std::string* error);
  // Records z = M r for these device vectors (the fine grid's cells) as a graph on `stream`.
  bool record(const double* r, double* z, cudaStream_t stream, std::string* error);
  void launch(cudaStream_t stream) const { cudaGraphLaunch(exec_, stream); }

 private:
  struct Level;
  void smoothLevel(Level& level, bool post, cudaStream_t stream);
  void sweeps(Level& level, int count, bool reverse, cudaStream_t stream);
  void boundarySweeps(Level& level, bool reverse, cudaStream_t stream);
  void restrictResidual(Level& fine, Level& coarse, cudaStream_t stream);
  void prolongateAdd(Level& fine, Level& coarse, cudaStream_t stream);
  void enqueueCycle(const double* r, double* z, cudaStream_t stream);

  std::vector<std::unique_ptr<Level>> levels_;
  kernels::TransferSides sides_;
  int sweeps_ = 0, coarsestSweeps_ = 0, boundarySweeps_ = 0;
  DeviceArray<float> alongX_, alongY_;  // the restriction's partial gathers
  cudaGraph_t graph_ = nullptr;
  cudaGraphExec_t exec_ = nullptr;
};

}  // namespace vp::gpu

// The corotation and stiffness assembly of a linear-tet deformable on a CUDA device: a thread
// per element runs kernels::corotateLinearTet (gpu_kernels/linear_tet_kernels.h), then a thread
// per node gathers its BCSR block row of stiffnessScale · R K Rᵀ and its elastic force
// (gpu_kernels/element_gather_kernels.h): the kernel bodies DeformableBody::corotateAndAssemble
// runs on the CPU, in a file built with --fmad=false, so the device gives the CPU's bits. Only
// declared where the CUDA path is compiled (VP_HAVE_CUDA); failures come back as false with the
// CUDA error text.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "gpu_kernels/element_gather_kernels.h"

namespace vp::gpu {

// Host arrays of the mesh and its step matrix's pattern (runtime/deform/deformable_body.h
// fills one: DeformableBody::linearTetAssembly).
struct LinearTetAssemblyView {
  int32_t nodes = 0;
  int64_t elements = 0;
  const int32_t* elementNodes = nullptr;   // 4 per element
  const double* restGradients = nullptr;   // 12 per element
  const double* restVolume = nullptr;      // per element
  double lambda = 0.0, mu = 0.0;           // Lamé parameters
  const int32_t* rowStart = nullptr;       // BCSR, nodes + 1
  kernels::ElementIncidenceView incidence;  // node -> (element, corner)
  const int32_t* scatter = nullptr;        // 16 block indices per element
};

class DeviceLinearTetAssembly {
 public:
  static std::unique_ptr<DeviceLinearTetAssembly> create(const LinearTetAssemblyView& view, std::string* error);
  ~DeviceLinearTetAssembly();
  DeviceLinearTetAssembly(const DeviceLinearTetAssembly&) = delete;
  DeviceLinearTetAssembly& operator=(const DeviceLinearTetAssembly&) = delete;

  // From host positions x (3 per node) and rotations quat (4 per element: the warm start in,
  // the result out): the block values (9 per block of the pattern) and the elastic force (3
  // per node), host arrays.
  bool assemble(const double* x, double* quat, double stiffnessScale, double* values, double* force,
                std::string* error);
  // `repeats` assemblies of the resident state of the last assemble(); device milliseconds each.
  bool timeAssemble(int repeats, double stiffnessScale, double* msPerAssembly, std::string* error);

 private:
  struct Impl;
  explicit DeviceLinearTetAssembly(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

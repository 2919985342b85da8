// The corotation and stiffness assembly of a deformable on a CUDA device, for BB elements of
// every degree: a thread per element runs kernels::corotateLinearTet (degree 1,
// gpu_kernels/linear_tet_kernels.h) or kernels::corotateBBElement (gpu_kernels/
// bb_element_kernels.h), then a thread per node gathers its BCSR block row of
// stiffnessScale · R K Rᵀ and its elastic force (gpu_kernels/element_gather_kernels.h): the
// kernel bodies DeformableBody::corotateAndAssemble runs on the CPU, in a file built with
// --fmad=false, so the device gives the CPU's bits. Only defined where the CUDA path is
// compiled (VP_HAVE_CUDA); failures come back as false with the CUDA error text.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "gpu_kernels/bb_element_kernels.h"
#include "gpu_kernels/element_gather_kernels.h"

namespace vp::gpu {

// Host arrays of the mesh and its step matrix's pattern (DeformableBody::elementAssemblyView
// fills one).
struct ElementAssemblyView {
  int degree = 1;
  int32_t nodes = 0;
  int64_t elements = 0;
  const int32_t* elementNodes = nullptr;    // kernels::elementNodeCount(degree) per element
  const double* restGradients = nullptr;    // 12 per element
  const double* restVolume = nullptr;       // per element
  double lambda = 0.0, mu = 0.0;            // Lamé parameters
  const int32_t* rowStart = nullptr;        // BCSR, nodes + 1
  kernels::ElementIncidenceView incidence;  // node -> (element, corner)
  const int32_t* scatter = nullptr;         // N x N block indices per element
  // Degree > 1 only: rest node positions (3 per node), the nodes' corner masks (N), the
  // stiffness terms (N² + 1 starts) and the rest stiffness's structure.
  const double* restPositions = nullptr;
  const uint8_t* nodeCorners = nullptr;
  kernels::BBStiffnessTermsView terms;
  kernels::BBStiffnessStructureView structure;
};

class DeviceElementAssembly {
 public:
  static std::unique_ptr<DeviceElementAssembly> create(const ElementAssemblyView& view, std::string* error);
  ~DeviceElementAssembly();
  DeviceElementAssembly(const DeviceElementAssembly&) = delete;
  DeviceElementAssembly& operator=(const DeviceElementAssembly&) = delete;

  // From host positions x (3 per node) and rotations quat (4 per element: the warm start in,
  // the result out): the block values (9 per block of the pattern) and the elastic force (3
  // per node), host arrays.
  bool assemble(const double* x, double* quat, double stiffnessScale, double* values, double* force,
                std::string* error);
  // `repeats` assemblies of the resident state of the last assemble(); device milliseconds each.
  bool timeAssemble(int repeats, double stiffnessScale, double* msPerAssembly, std::string* error);

 private:
  struct Impl;
  explicit DeviceElementAssembly(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

// A MAC grid's velocity resident on a CUDA device, advecting itself and cell-centred scalars
// there: one thread per face or cell through the kernel bodies the CPU's advection runs
// (gpu_kernels/advection_kernels.h: advectFace, maccormackFace; scalar_advection_kernels.h),
// compiled without contraction (--fmad=false), and the conserved field's sums in the CPU's
// order, so every value gets the CPU's bits (advectVelocity without a skip mask;
// advectCellScalars without keepBeyond or a level set). Only declared where the CUDA path is
// compiled (VP_HAVE_CUDA); failures come back as false with the CUDA error text.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "gpu_kernels/advection_kernels.h"
#include "gpu_kernels/mac_layout.h"

namespace vp::gpu {

// advectCellScalars' options the device takes, as host arrays.
struct ScalarAdvectionOptions {
  const uint8_t* faces = nullptr;       // per cell (CellOpenFaces); null: plain trilinear sampling
  const uint8_t* blockOpen = nullptr;
  const double* solidValues = nullptr;  // per field; null: solid cells keep their values
  int conservedField = -1;              // its total kept less what the Open sides carried out
};

class DeviceAdvection {
 public:
  // The grid's layout (its Open sides: those that are not Walls) and velocity from host arrays.
  static std::unique_ptr<DeviceAdvection> create(const kernels::MacVelocityView& host, const kernels::MacLayout& layout,
                                                 std::string* error);
  ~DeviceAdvection();
  DeviceAdvection(const DeviceAdvection&) = delete;
  DeviceAdvection& operator=(const DeviceAdvection&) = delete;

  // Replaces the device's velocity by itself advected over dt (semi-Lagrangian, or MacCormack).
  bool advect(double dt, bool maccormack, std::string* error);
  // Advects `count` host fields (cell order, in place) by the device's velocity over dt.
  bool advectScalars(double* const* fields, int count, double dt, bool maccormack,
                     const ScalarAdvectionOptions& options, std::string* error);
  // The device's velocity into host arrays of the view's face counts.
  bool download(double* const u[3], std::string* error);
  // Device milliseconds per advect(), over `repeats` (the velocity changes as it runs).
  bool timeAdvect(int repeats, double dt, bool maccormack, double* msPerAdvect, std::string* error);

 private:
  struct Impl;
  explicit DeviceAdvection(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

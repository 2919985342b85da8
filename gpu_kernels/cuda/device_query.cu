#include <cuda_runtime.h>

#include "gpu_kernels/device_query.h"

namespace vp::gpu {

bool cudaCompiled() { return true; }

int cudaDeviceCount() {
  int count = 0;
  // No driver or no device is an ordinary answer here, not an error.
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return count;
}

bool cudaDeviceProperties(int index, DeviceProperties* out) {
  cudaDeviceProp p{};
  if (index < 0 || index >= cudaDeviceCount() || cudaGetDeviceProperties(&p, index) != cudaSuccess) {
    cudaGetLastError();
    return false;
  }
  out->name = p.name;
  out->totalMemoryBytes = p.totalGlobalMem;
  out->computeCapabilityMajor = p.major;
  out->computeCapabilityMinor = p.minor;
  out->multiprocessors = p.multiProcessorCount;
  return true;
}

}  // namespace vp::gpu

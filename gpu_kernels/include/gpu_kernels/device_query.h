// Whether the CUDA path is compiled in and how many devices it can use right now. Works
// (answering 0) on machines without a GPU or driver.
#pragma once

#include <cstdint>
#include <string>

namespace vp::gpu {

bool cudaCompiled();
int cudaDeviceCount();

struct DeviceProperties {
  std::string name;
  uint64_t totalMemoryBytes = 0;
  int computeCapabilityMajor = 0, computeCapabilityMinor = 0;
  int multiprocessors = 0;
};
// False when `index` names no usable device.
bool cudaDeviceProperties(int index, DeviceProperties* out);

}  // namespace vp::gpu

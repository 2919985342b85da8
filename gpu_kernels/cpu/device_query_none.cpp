// Built without CUDA: the library still runs everything on the CPU.
#include "gpu_kernels/device_query.h"

namespace vp::gpu {

bool cudaCompiled() { return false; }
int cudaDeviceCount() { return 0; }
bool cudaDeviceProperties(int, DeviceProperties*) { return false; }

}  // namespace vp::gpu

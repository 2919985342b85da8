// Lets one kernel body compile for the CPU (called from parallel_for) and for CUDA (called
// from a __global__ launcher): a kernel body is a function of an index and plain arrays.
#pragma once

#include <cstdint>

#if defined(__CUDACC__)
#define VP_HOST_DEVICE __host__ __device__
#else
#define VP_HOST_DEVICE
#endif

namespace vp::kernels {

// Sets a flag that other workers of the same pass may set at the same time (they all store 1,
// and nobody reads it during the pass): a relaxed atomic store on the CPU, so the race is a
// defined one, and a plain byte store on the device.
VP_HOST_DEVICE inline void raiseSharedFlag(uint8_t* flag) {
#if defined(__CUDA_ARCH__)
  *reinterpret_cast<volatile uint8_t*>(flag) = 1;
#else
  __atomic_store_n(flag, static_cast<uint8_t>(1), __ATOMIC_RELAXED);
#endif
}

}  // namespace vp::kernels

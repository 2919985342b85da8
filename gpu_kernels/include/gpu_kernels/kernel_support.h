// Lets one kernel body compile for the CPU (called from parallel_for) and for CUDA (called
// from a __global__ launcher): a kernel body is a function of an index and plain arrays.
#pragma once

#if defined(__CUDACC__)
#define VP_HOST_DEVICE __host__ __device__
#else
#define VP_HOST_DEVICE
#endif

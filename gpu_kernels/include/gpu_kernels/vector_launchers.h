// CUDA launchers for the vector kernels; device pointers in, status out. Only declared when
// the CUDA path is compiled (VP_HAVE_CUDA).
#pragma once

#include <cstdint>

namespace vp::gpu {

// Return false (with the CUDA error text in *error) if the launch failed.
bool axpy(int64_t n, double a, const double* x, double* y, const char** error);
bool xpby(int64_t n, const double* x, double b, double* y, const char** error);

}  // namespace vp::gpu

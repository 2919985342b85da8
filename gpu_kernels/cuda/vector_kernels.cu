#include <cuda_runtime.h>

#include "gpu_kernels/vector_kernels.h"
#include "gpu_kernels/vector_launchers.h"

namespace vp::gpu {
namespace {

constexpr int kBlock = 256;

__global__ void axpyKernel(int64_t n, double a, const double* x, double* y) {
  int64_t i = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  if (i < n) kernels::axpyItem(i, a, x, y);
}

__global__ void xpbyKernel(int64_t n, const double* x, double b, double* y) {
  int64_t i = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  if (i < n) kernels::xpbyItem(i, x, b, y);
}

bool check(const char** error) {
  cudaError_t e = cudaGetLastError();
  if (e == cudaSuccess) return true;
  if (error) *error = cudaGetErrorString(e);
  return false;
}

unsigned blocksFor(int64_t n) { return static_cast<unsigned>((n + kBlock - 1) / kBlock); }

}  // namespace

bool axpy(int64_t n, double a, const double* x, double* y, const char** error) {
  if (n <= 0) return true;
  axpyKernel<<<blocksFor(n), kBlock>>>(n, a, x, y);
  return check(error);
}

bool xpby(int64_t n, const double* x, double b, double* y, const char** error) {
  if (n <= 0) return true;
  xpbyKernel<<<blocksFor(n), kBlock>>>(n, x, b, y);
  return check(error);
}

}  // namespace vp::gpu

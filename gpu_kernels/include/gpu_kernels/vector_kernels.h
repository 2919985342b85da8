// Element-wise vector kernels used by the iterative solvers (CG and friends). Written once,
// run by the CPU parallel_for and by the CUDA launchers in cuda/vector_kernels.cu.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

// y[i] += a * x[i]
template <class T>
VP_HOST_DEVICE inline void axpyItem(int64_t i, T a, const T* x, T* y) {
  y[i] += a * x[i];
}

// y[i] = x[i] + b * y[i]   (the CG search-direction update)
template <class T>
VP_HOST_DEVICE inline void xpbyItem(int64_t i, const T* x, T b, T* y) {
  y[i] = x[i] + b * y[i];
}

// The CG's step over [begin, end): x += alpha p, r -= alpha q, returning the partial r . r in
// index order (the same sums as axpy, axpy and dotRange one after another, in one pass).
template <class T>
VP_HOST_DEVICE inline double cgStepRange(int64_t begin, int64_t end, T alpha, const T* p, const T* q, T* x, T* r) {
  double sum = 0.0;
  for (int64_t i = begin; i < end; ++i) {
    x[i] += alpha * p[i];
    r[i] += -alpha * q[i];
    sum += static_cast<double>(r[i]) * static_cast<double>(r[i]);
  }
  return sum;
}

// partial dot product over [begin, end), in index order (deterministic)
template <class T>
VP_HOST_DEVICE inline double dotRange(int64_t begin, int64_t end, const T* x, const T* y) {
  double sum = 0.0;
  for (int64_t i = begin; i < end; ++i) sum += static_cast<double>(x[i]) * static_cast<double>(y[i]);
  return sum;
}

}  // namespace vp::kernels

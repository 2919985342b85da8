#include "linalg/vector_ops.h"

#include <cstring>

#include "core/parallel_for.h"
#include "gpu_kernels/vector_kernels.h"

namespace vp::vec {

double dot(TaskSystem& tasks, int64_t n, const double* x, const double* y) {
  return parallelReduce<double>(tasks, n, kGrain,
                                [&](int64_t b, int64_t e) { return kernels::dotRange(b, e, x, y); });
}

void axpy(TaskSystem& tasks, int64_t n, double a, const double* x, double* y) {
  parallelFor(tasks, n, kGrain, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) kernels::axpyItem(i, a, x, y);
  });
}

void xpby(TaskSystem& tasks, int64_t n, const double* x, double b, double* y) {
  parallelFor(tasks, n, kGrain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) kernels::xpbyItem(i, x, b, y);
  });
}

double cgStep(TaskSystem& tasks, int64_t n, double alpha, const double* p, const double* q, double* x, double* r) {
  return parallelReduce<double>(tasks, n, kGrain,
                                [&](int64_t b, int64_t e) { return kernels::cgStepRange(b, e, alpha, p, q, x, r); });
}

void copy(TaskSystem& tasks, int64_t n, const double* x, double* y) {
  parallelFor(tasks, n, kGrain, [&](int64_t b, int64_t e) {
    std::memcpy(y + b, x + b, static_cast<size_t>(e - b) * sizeof(double));
  });
}

}  // namespace vp::vec

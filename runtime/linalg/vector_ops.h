// Parallel vector operations over double arrays for the iterative solvers, built on the
// kernel bodies in gpu_kernels/ and deterministic parallel_for/parallel_reduce.
#pragma once

#include <cstdint>

#include "core/task_system.h"

namespace vp::vec {

constexpr int64_t kGrain = 4096;  // fixed chunk: results never depend on the worker count

double dot(TaskSystem& tasks, int64_t n, const double* x, const double* y);
void axpy(TaskSystem& tasks, int64_t n, double a, const double* x, double* y);  // y += a x
void xpby(TaskSystem& tasks, int64_t n, const double* x, double b, double* y);  // y = x + b y
void copy(TaskSystem& tasks, int64_t n, const double* x, double* y);
// x += alpha p; r -= alpha q; returns r . r: the CG's update in one pass over the four vectors
// instead of three passes (bitwise the same results as axpy, axpy, dot).
double cgStep(TaskSystem& tasks, int64_t n, double alpha, const double* p, const double* q, double* x, double* r);

}  // namespace vp::vec

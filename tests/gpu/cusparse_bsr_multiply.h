// cuSPARSE's BSR product (cusparseDbsrmv, 3x3 row-major blocks) on a DeviceBlockSystem's BCSR
// copy: the library baseline the BIN-BCSR kernel is measured against.
#pragma once

#include <string>

#include "gpu_kernels/device_block_system.h"

namespace vp::gpu_test {

// y = A x for host vectors (the check that the baseline computes the same product).
bool cusparseBsrMultiply(const gpu::DeviceBcsr& bcsr, const double* x, double* y, std::string* error);

// `repeats` timed products between the resident vectors; device milliseconds per product.
bool timeCusparseBsrMultiply(const gpu::DeviceBcsr& bcsr, int repeats, double* msPerProduct, std::string* error);

}  // namespace vp::gpu_test

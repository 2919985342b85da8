#include "cusparse_bsr_multiply.h"

#include <cuda_runtime.h>
#include <cusparse.h>

namespace vp::gpu_test {

namespace {

// A cuSPARSE handle and the BSR descriptor of the system's BCSR copy.
class BsrProduct {
 public:
  explicit BsrProduct(const gpu::DeviceBcsr& bcsr) : bcsr_(bcsr) {
    ok_ = cusparseCreate(&handle_) == CUSPARSE_STATUS_SUCCESS &&
          cusparseCreateMatDescr(&descr_) == CUSPARSE_STATUS_SUCCESS;
    if (ok_) {
      cusparseSetMatType(descr_, CUSPARSE_MATRIX_TYPE_GENERAL);
      cusparseSetMatIndexBase(descr_, CUSPARSE_INDEX_BASE_ZERO);
    }
  }
  ~BsrProduct() {
    if (descr_) cusparseDestroyMatDescr(descr_);
    if (handle_) cusparseDestroy(handle_);
  }
  bool ok() const { return ok_; }
  bool run() {
    const double one = 1.0, zero = 0.0;
    return cusparseDbsrmv(handle_, CUSPARSE_DIRECTION_ROW, CUSPARSE_OPERATION_NON_TRANSPOSE, bcsr_.rows, bcsr_.rows,
                          static_cast<int>(bcsr_.blocks), &one, descr_, bcsr_.values, bcsr_.rowStart, bcsr_.columns, 3,
                          bcsr_.x, &zero, bcsr_.y) == CUSPARSE_STATUS_SUCCESS;
  }

 private:
  gpu::DeviceBcsr bcsr_;
  cusparseHandle_t handle_ = nullptr;
  cusparseMatDescr_t descr_ = nullptr;
  bool ok_ = false;
};

}  // namespace

bool cusparseBsrMultiply(const gpu::DeviceBcsr& bcsr, const double* x, double* y, std::string* error) {
  BsrProduct product(bcsr);
  const size_t bytes = 3 * static_cast<size_t>(bcsr.rows) * sizeof(double);
  const bool ok = product.ok() && cudaMemcpy(bcsr.x, x, bytes, cudaMemcpyHostToDevice) == cudaSuccess &&
                  product.run() && cudaMemcpy(y, bcsr.y, bytes, cudaMemcpyDeviceToHost) == cudaSuccess;
  if (!ok) *error = "cuSPARSE BSR product failed";
  return ok;
}

bool timeCusparseBsrMultiply(const gpu::DeviceBcsr& bcsr, int repeats, double* msPerProduct, std::string* error) {
  BsrProduct product(bcsr);
  bool ok = product.ok() && product.run();
  cudaEvent_t start, stop;
  cudaEventCreate(&start);
  cudaEventCreate(&stop);
  cudaEventRecord(start);
  for (int i = 0; ok && i < repeats; ++i) ok = product.run();
  cudaEventRecord(stop);
  cudaEventSynchronize(stop);
  float ms = 0;
  cudaEventElapsedTime(&ms, start, stop);
  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  if (!ok) *error = "cusparseDbsrmv failed";
  *msPerProduct = ms / (repeats > 0 ? repeats : 1);
  return ok && cudaGetLastError() == cudaSuccess;
}

}  // namespace vp::gpu_test

// A symmetric positive definite system of 3x3 blocks resident on a CUDA device: the matrix in
// BIN-BCSR (gpu_kernels/block_row_kernels.h), optionally a BCSR copy for the baseline
// product, the block-Jacobi inverse, the filter of free degrees of freedom, and the CG's
// vectors. Only declared where the CUDA path is compiled (VP_HAVE_CUDA); every call reports a
// CUDA failure as false with the CUDA error text, never by aborting.
//
// The CG is the CPU's filtered, block-Jacobi preconditioned CG (linalg/conjugate_gradient.h)
// with the filter a 0/1 mask per degree of freedom (pinned nodes), in two forms:
//   Fused:   three launches per iteration (q = A p with p.q; the x, r, z updates with r.z and
//            r.r; the new direction), every scalar stays on the device and the host looks at
//            the stop flag only every kStopCheckInterval iterations;
//   Unfused: one launch per vector operation and the scalars read back twice per iteration,
//            the textbook GPU CG the fused form is measured against.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "gpu_kernels/block_row_kernels.h"

namespace vp::gpu {

struct HostBlockSystem {
  kernels::BinBcsrView<double> matrix;
  int32_t slots = 0;                        // matrix.binSlotStart[matrix.bins]
  const double* inverseDiagonal = nullptr;  // bins * 9 * kBinRows, lane-minor
  const double* freeDofs = nullptr;         // 3 * rows of 1 (free) or 0 (pinned); null: all free
  // The same matrix in BCSR, for the baseline products (null: none).
  const int32_t* bcsrRowStart = nullptr;
  const int32_t* bcsrColumns = nullptr;
  const double* bcsrValues = nullptr;
};

enum class DeviceCgForm { Fused, Unfused };

struct DeviceCgResult {
  int iterations = 0;
  double relativeResidual = 0.0;  // |r| / |filtered b|, of the CG's recurrence
  bool converged = false;
  double deviceMs = 0.0;  // the iterations alone, between two device events
  int launches = 0;       // kernel launches the iterations made
};

// Device pointers of the BCSR copy and of two resident vectors, for a caller's own kernels or
// library calls (the cuSPARSE baseline in the benchmarks).
struct DeviceBcsr {
  int32_t rows = 0;
  int64_t blocks = 0;
  const int32_t* rowStart = nullptr;
  const int32_t* columns = nullptr;
  const double* values = nullptr;
  double* x = nullptr;
  double* y = nullptr;
};

class DeviceBlockSystem {
 public:
  static constexpr int kStopCheckInterval = 8;

  // Null, with the reason in *error, when no device can be used or memory runs out.
  static std::unique_ptr<DeviceBlockSystem> create(const HostBlockSystem& host, std::string* error);
  ~DeviceBlockSystem();
  DeviceBlockSystem(const DeviceBlockSystem&) = delete;
  DeviceBlockSystem& operator=(const DeviceBlockSystem&) = delete;

  int32_t rows() const;
  // y = A x for host vectors, through the BIN-BCSR kernel or (bcsr) the BCSR one.
  bool multiply(const double* x, double* y, bool bcsr, std::string* error);
  // `repeats` products between resident vectors; device milliseconds per product.
  bool timeMultiply(int repeats, bool bcsr, double* msPerProduct, std::string* error);
  // Solves A x = b from the x given (host vectors; x is overwritten with the result).
  bool solve(const double* b, double* x, double relativeTolerance, int maxIterations, DeviceCgForm form,
             DeviceCgResult* result, std::string* error);
  // Null pointers when the system was created without its BCSR copy.
  DeviceBcsr bcsr() const;

 private:
  struct Impl;
  explicit DeviceBlockSystem(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

// A symmetric positive definite system of 3x3 blocks resident on a CUDA device: the matrix in
// BIN-BCSR (gpu_kernels/block_row_kernels.h), optionally a BCSR copy for the baseline
// product, the block-Jacobi inverse, the node constraints (gpu_kernels/constraint_kernels.h),
// and the CG's vectors. Every call reports a CUDA failure as false with the CUDA error text,
// never by aborting; without the CUDA path (gpu_kernels/cpu/device_block_system_none.cpp)
// create says the build has none.
//
// The CG is the CPU's filtered, block-Jacobi preconditioned CG (linalg/conjugate_gradient.h)
// with the filter the node constraints' projection, in two forms:
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
  // Per node a kernels::NodeConstraintKind, and 3 per node the contact normals (read where the
  // kind is kNodeContact); null: every node free.
  const uint8_t* nodeKind = nullptr;
  const double* nodeNormal = nullptr;
  // The same matrix in BCSR, for the baseline products (null: none).
  const int32_t* bcsrRowStart = nullptr;
  const int32_t* bcsrColumns = nullptr;
  const double* bcsrValues = nullptr;
};

enum class DeviceCgForm { Fused, Unfused };

struct DeviceCgResult {
  int iterations = 0;
  bool stoppedByCaller = false;  // DeviceCgControl::stop said so
  double relativeResidual = 0.0;  // |r| / |filtered b|, of the CG's recurrence
  bool converged = false;
  double deviceMs = 0.0;  // the iterations alone, between two device events
  int launches = 0;       // kernel launches the iterations made
};

// Looked at by the host each kStopCheckInterval iterations, with the relative residual then:
// true stops the solve there (a frame budget's deadline, say).
struct DeviceCgControl {
  bool (*stop)(void* context, int iterations, double relativeResidual) = nullptr;
  void* context = nullptr;
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
  // New values in the pattern the system was created with (BIN-BCSR values and diagonal, the
  // block-Jacobi inverse), and new constraints; the layouts of HostBlockSystem.
  bool setValues(const double* values, const double* diagonal, const double* inverseDiagonal, std::string* error);
  bool setConstraints(const uint8_t* nodeKind, const double* nodeNormal, std::string* error);
  // Solves A x = b from the x given (host vectors; x is overwritten with the result). Without
  // a filtered right-hand side (|F b| = 0) the answer is x with its free part removed, as on
  // the CPU.
  bool solve(const double* b, double* x, double relativeTolerance, int maxIterations, DeviceCgForm form,
             DeviceCgResult* result, std::string* error, const DeviceCgControl& control = {});
  // Null pointers when the system was created without its BCSR copy.
  DeviceBcsr bcsr() const;

 private:
  struct Impl;
  explicit DeviceBlockSystem(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vp::gpu

// A 3x3-block matrix in BIN-BCSR, the GPU's layout (gpu_kernels/block_row_kernels.h says
// what each array holds), built from the CPU's BCSR. The pattern is built once; a matrix whose
// values change every step (a deformable's step matrix) refreshes only the values, through
// the map from each stored block to its BCSR block.
#pragma once

#include <cstdint>

#include "core/allocator.h"
#include "core/task_system.h"
#include "gpu_kernels/block_row_kernels.h"
#include "linalg/block_sparse_matrix.h"

namespace vp {

template <class Scalar>
struct BinBcsrMatrix {
  int32_t rows = 0;
  Array<int32_t> binSlotStart;
  Array<int32_t> columns;
  Array<Scalar> values;
  Array<Scalar> diagonal;
  Array<int32_t> diagonalPosition;
  // Per slot lane: the BCSR block stored there (-1: padding); per row: its diagonal's.
  Array<int32_t> sourceBlock;
  Array<int32_t> sourceDiagonal;

  int32_t bins() const { return static_cast<int32_t>(binSlotStart.size()) - 1; }
  int32_t slots() const { return binSlotStart.empty() ? 0 : binSlotStart.back(); }
  kernels::BinBcsrView<Scalar> view() const;
  // y = A x through the kernel body, one row at a time (the CPU's way of running it).
  void multiply(TaskSystem& tasks, const double* x, double* y) const;
};

// Pattern and values of `source` in BIN-BCSR (values converted to Scalar).
template <class Scalar, class SourceScalar>
void buildBinBcsr(const BlockSparseMatrix<SourceScalar>& source, BinBcsrMatrix<Scalar>* out);

// The values of `source`, whose pattern must be the one `matrix` was built from.
template <class Scalar, class SourceScalar>
void refreshBinBcsrValues(const BlockSparseMatrix<SourceScalar>& source, BinBcsrMatrix<Scalar>* matrix);

// The inverses of the diagonal blocks, lane-minor like BinBcsrMatrix::diagonal (what
// kernels::blockJacobiRow reads); a singular block's inverse is zero (the row is not
// preconditioned: a pinned node's row after filtering, say).
template <class Scalar>
void binnedInverseDiagonal(const BlockSparseMatrix<double>& source, Array<Scalar>* out);

// One 3x3 block per row (9 per row, row-major: the CPU's block-Jacobi inverses) laid out
// lane-minor like BinBcsrMatrix::diagonal.
template <class Scalar>
void binnedBlocks(const double* blocks, int32_t rows, Array<Scalar>* out);

}  // namespace vp

// Symmetric sparse matrix of 3x3 blocks in block-compressed-row form (BCSR), both triangles
// stored so that a row-parallel multiply needs no atomics and is deterministic.
//
// Layout: block row r holds blocks rowStart[r] .. rowStart[r+1]-1, sorted by column;
// columns[k] is the block column of block k; values[9k .. 9k+8] its entries, row-major.
// diagonal[r] is the index of block (r, r). Scalar is the storage type (float halves the
// memory traffic of the multiply, which is what bounds it); vectors are always double.
#pragma once

#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "core/task_system.h"

namespace vp {

template <class Scalar>
struct BlockSparseMatrix {
  int32_t blockRows = 0;
  Array<int32_t> rowStart;
  Array<int32_t> columns;
  Array<int32_t> diagonal;
  Array<Scalar> values;

  int64_t blockCount() const { return static_cast<int64_t>(columns.size()); }
  // Index of block (row, column), or -1 if it is not in the pattern.
  int32_t find(int32_t row, int32_t column) const;
  void setZero();
  // y = A x, x and y of length 3 * blockRows (must not alias).
  void multiply(TaskSystem& tasks, const double* x, double* y) const;
};

// Builds the pattern of a matrix coupling every pair of nodes that share an element, and the
// scatter table: scatter[e * n * n + a * n + b] is the block index of (nodes[e*n+a],
// nodes[e*n+b]) for element e with n nodes. The pattern is the same for any worker count.
template <class Scalar>
void buildElementPattern(int32_t nodeCount, const int32_t* elementNodes, int64_t elementCount, int nodesPerElement,
                         BlockSparseMatrix<Scalar>* matrix, Array<int32_t>* scatter);

extern template struct BlockSparseMatrix<float>;
extern template struct BlockSparseMatrix<double>;

}  // namespace vp

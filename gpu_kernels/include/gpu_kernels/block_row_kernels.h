// Row products of a sparse matrix of 3x3 blocks, in the two layouts the solvers use:
//   BCSR      the CPU's (linalg/block_sparse_matrix.h): a row's blocks one after another,
//             sorted by column, each block's 9 entries row-major;
//   BIN-BCSR  the GPU's (the thesis' layout): rows in bins of kBinRows, one warp per bin and
//             row of the blocks (three per bin), one thread per scalar row. Inside a bin the blocks are stored column-major: the k-th
//             off-diagonal block of every row of the bin sits side by side (a "slot" of
//             kBinRows lanes), and within a slot each of the 9 entries is a run of kBinRows
//             values, so a warp's loads of one entry are one coalesced transaction. A bin is
//             padded to its longest row (column -1 marks padding). Diagonal blocks are stored
//             apart, in the same lane-minor form, for the block-Jacobi preconditioner.
// Both products add a row's blocks in column order (BIN-BCSR inserts the diagonal at its
// column's place), so on one machine the two give bitwise the same y.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"

namespace vp::kernels {

constexpr int32_t kBinRows = 32;  // one warp

// y += row i of a 3x3 block times xc, the block's entry (i, j) at aRow[j * stride].
template <class Scalar>
VP_HOST_DEVICE inline void addBlockRowProduct(const Scalar* aRow, int64_t stride, const double* xc, double& y) {
  y += aRow[0] * xc[0] + aRow[stride] * xc[1] + aRow[2 * stride] * xc[2];
}

// (y0, y1, y2) += A xc for a 3x3 block whose entry (i, j) is a[(3 i + j) * stride].
template <class Scalar>
VP_HOST_DEVICE inline void addBlockProduct(const Scalar* a, int64_t stride, const double* xc, double& y0, double& y1,
                                           double& y2) {
  addBlockRowProduct(a, stride, xc, y0);
  addBlockRowProduct(a + 3 * stride, stride, xc, y1);
  addBlockRowProduct(a + 6 * stride, stride, xc, y2);
}

// y_row = (A x)_row for BCSR: blocks rowStart[row] .. rowStart[row + 1] - 1.
template <class Scalar>
VP_HOST_DEVICE inline void bcsrRowProduct(int64_t row, const int32_t* rowStart, const int32_t* columns,
                                          const Scalar* values, const double* x, double* y) {
  double y0 = 0, y1 = 0, y2 = 0;
  for (int32_t k = rowStart[row]; k < rowStart[row + 1]; ++k)
    addBlockProduct(values + 9 * static_cast<int64_t>(k), 1, x + 3 * static_cast<int64_t>(columns[k]), y0, y1, y2);
  y[3 * row] = y0;
  y[3 * row + 1] = y1;
  y[3 * row + 2] = y2;
}

// A BIN-BCSR matrix as plain arrays. Bin b owns slots binSlotStart[b] .. binSlotStart[b + 1] - 1;
// lane l of slot s (row b * kBinRows + l) has block column columns[s * kBinRows + l] (-1:
// padding) and entry e at values[(9 s + e) * kBinRows + l]. The diagonal block of that row has
// entry e at diagonal[(9 b + e) * kBinRows + l] and stands before the row's
// diagonalPosition[row]-th off-diagonal block (-1: the row has no diagonal block).
template <class Scalar>
struct BinBcsrView {
  int32_t rows = 0;
  int32_t bins = 0;
  const int32_t* binSlotStart = nullptr;  // bins + 1
  const int32_t* columns = nullptr;       // slots * kBinRows
  const Scalar* values = nullptr;         // slots * 9 * kBinRows
  const Scalar* diagonal = nullptr;       // bins * 9 * kBinRows
  const int32_t* diagonalPosition = nullptr;  // rows
};

// Offset of entry 0 of lane `lane` of a lane-minor block group (a slot, or a bin's diagonals).
VP_HOST_DEVICE inline int64_t laneBlockOffset(int64_t group, int32_t lane) {
  return group * 9 * kBinRows + lane;
}

// (A x) at scalar row 3 row + component for BIN-BCSR, the blocks added in column order. The
// GPU runs one thread per scalar row: the three warps of a bin read entries 3 c .. 3 c + 2 of
// each slot, every load coalesced. Each scalar row's sum is the BCSR's, term for term.
template <class Scalar>
VP_HOST_DEVICE inline double binBcsrComponentProduct(int32_t row, int component, const BinBcsrView<Scalar>& m,
                                                     const double* x) {
  const int32_t bin = row / kBinRows, lane = row % kBinRows;
  const int32_t first = m.binSlotStart[bin], last = m.binSlotStart[bin + 1];
  const int32_t diagonalAt = m.diagonalPosition[row];
  const int64_t entry = 3 * static_cast<int64_t>(component) * kBinRows;
  double y = 0;
  for (int32_t s = first;; ++s) {
    if (s - first == diagonalAt)
      addBlockRowProduct(m.diagonal + laneBlockOffset(bin, lane) + entry, kBinRows, x + 3 * static_cast<int64_t>(row), y);
    if (s == last) break;
    const int32_t column = m.columns[static_cast<int64_t>(s) * kBinRows + lane];
    if (column < 0) continue;  // padding (a row's padding follows all its blocks)
    addBlockRowProduct(m.values + laneBlockOffset(s, lane) + entry, kBinRows, x + 3 * static_cast<int64_t>(column), y);
  }
  return y;
}

// y_row = (A x)_row for BIN-BCSR.
template <class Scalar>
VP_HOST_DEVICE inline void binBcsrRowProduct(int32_t row, const BinBcsrView<Scalar>& m, const double* x, double* y) {
  for (int c = 0; c < 3; ++c) y[3 * static_cast<int64_t>(row) + c] = binBcsrComponentProduct(row, c, m, x);
}

// (D_row^-1 r_row) at component c, the inverse diagonal blocks stored lane-minor like
// BinBcsrView::diagonal.
template <class Scalar>
VP_HOST_DEVICE inline double blockJacobiComponent(int32_t row, int component, const Scalar* inverseDiagonal,
                                                  const double* r) {
  double z = 0;
  addBlockRowProduct(inverseDiagonal + laneBlockOffset(row / kBinRows, row % kBinRows) + 3 * component * kBinRows,
                     kBinRows, r + 3 * static_cast<int64_t>(row), z);
  return z;
}

// z_row = D_row^-1 r_row (r and z must not alias).
template <class Scalar>
VP_HOST_DEVICE inline void blockJacobiRow(int32_t row, const Scalar* inverseDiagonal, const double* r, double* z) {
  for (int c = 0; c < 3; ++c) z[3 * static_cast<int64_t>(row) + c] = blockJacobiComponent(row, c, inverseDiagonal, r);
}

}  // namespace vp::kernels

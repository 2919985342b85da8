#include "linalg/bin_bcsr_matrix.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"

namespace vp {
namespace {

using kernels::kBinRows;

template <class Scalar, class SourceScalar>
void copyBlockLaneMinor(const SourceScalar* block, Scalar* laneEntry0) {
  for (int e = 0; e < 9; ++e) laneEntry0[e * kBinRows] = static_cast<Scalar>(block[e]);
}

}  // namespace

template <class Scalar>
kernels::BinBcsrView<Scalar> BinBcsrMatrix<Scalar>::view() const {
  kernels::BinBcsrView<Scalar> v;
  v.rows = rows;
  v.bins = bins();
  v.binSlotStart = binSlotStart.data();
  v.columns = columns.data();
  v.values = values.data();
  v.diagonal = diagonal.data();
  v.diagonalPosition = diagonalPosition.data();
  return v;
}

template <class Scalar>
void BinBcsrMatrix<Scalar>::multiply(TaskSystem& tasks, const double* x, double* y) const {
  const kernels::BinBcsrView<Scalar> m = view();
  parallelFor(tasks, rows, 512, [&](int64_t rowBegin, int64_t rowEnd) {
    for (int64_t r = rowBegin; r < rowEnd; ++r) kernels::binBcsrRowProduct(static_cast<int32_t>(r), m, x, y);
  });
}

template <class Scalar, class SourceScalar>
void buildBinBcsr(const BlockSparseMatrix<SourceScalar>& source, BinBcsrMatrix<Scalar>* out) {
  BinBcsrMatrix<Scalar>& m = *out;
  m.rows = source.blockRows;
  const int32_t bins = (m.rows + kBinRows - 1) / kBinRows;
  m.binSlotStart.assign(static_cast<size_t>(bins) + 1, 0);
  m.diagonalPosition.assign(static_cast<size_t>(m.rows), -1);
  m.sourceDiagonal.assign(static_cast<size_t>(m.rows), -1);
  // A row's off-diagonal count fixes its bin's width; the diagonal's place is the number of
  // the row's blocks left of it.
  for (int32_t r = 0; r < m.rows; ++r) {
    int32_t offDiagonal = 0;
    for (int32_t k = source.rowStart[r]; k < source.rowStart[r + 1]; ++k) {
      if (source.columns[k] == r) {
        m.diagonalPosition[r] = offDiagonal;
        m.sourceDiagonal[r] = k;
      } else {
        ++offDiagonal;
      }
    }
    int32_t& width = m.binSlotStart[r / kBinRows + 1];
    width = std::max(width, offDiagonal);
  }
  for (int32_t b = 0; b < bins; ++b) m.binSlotStart[b + 1] += m.binSlotStart[b];
  const size_t laneCount = static_cast<size_t>(m.slots()) * kBinRows;
  m.columns.assign(laneCount, -1);
  m.sourceBlock.assign(laneCount, -1);
  for (int32_t r = 0; r < m.rows; ++r) {
    int64_t slot = m.binSlotStart[r / kBinRows];
    for (int32_t k = source.rowStart[r]; k < source.rowStart[r + 1]; ++k) {
      if (source.columns[k] == r) continue;
      const size_t lane = static_cast<size_t>(slot++ * kBinRows + r % kBinRows);
      m.columns[lane] = source.columns[k];
      m.sourceBlock[lane] = k;
    }
  }
  refreshBinBcsrValues(source, out);
}

template <class Scalar, class SourceScalar>
void refreshBinBcsrValues(const BlockSparseMatrix<SourceScalar>& source, BinBcsrMatrix<Scalar>* matrix) {
  BinBcsrMatrix<Scalar>& m = *matrix;
  m.values.assign(static_cast<size_t>(m.slots()) * 9 * kBinRows, Scalar(0));
  m.diagonal.assign(static_cast<size_t>(m.bins()) * 9 * kBinRows, Scalar(0));
  for (int64_t s = 0; s < m.slots(); ++s)
    for (int32_t lane = 0; lane < kBinRows; ++lane) {
      const int32_t k = m.sourceBlock[static_cast<size_t>(s * kBinRows + lane)];
      if (k >= 0)
        copyBlockLaneMinor(&source.values[9 * static_cast<size_t>(k)], &m.values[kernels::laneBlockOffset(s, lane)]);
    }
  for (int32_t r = 0; r < m.rows; ++r) {
    const int32_t k = m.sourceDiagonal[r];
    if (k >= 0)
      copyBlockLaneMinor(&source.values[9 * static_cast<size_t>(k)],
                         &m.diagonal[kernels::laneBlockOffset(r / kBinRows, r % kBinRows)]);
  }
}

template <class Scalar>
void binnedInverseDiagonal(const BlockSparseMatrix<double>& source, Array<Scalar>* out) {
  using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  const int32_t bins = (source.blockRows + kBinRows - 1) / kBinRows;
  out->assign(static_cast<size_t>(bins) * 9 * kBinRows, Scalar(0));
  for (int32_t r = 0; r < source.blockRows; ++r) {
    if (source.diagonal[r] < 0) continue;
    const Mat3R d = Eigen::Map<const Mat3R>(&source.values[9 * static_cast<size_t>(source.diagonal[r])]);
    bool invertible = false;
    Mat3R inverse;
    d.computeInverseWithCheck(inverse, invertible);
    if (!invertible || !inverse.allFinite()) continue;
    copyBlockLaneMinor(inverse.data(), &(*out)[kernels::laneBlockOffset(r / kBinRows, r % kBinRows)]);
  }
}

template <class Scalar>
void binnedBlocks(const double* blocks, int32_t rows, Array<Scalar>* out) {
  const int32_t bins = (rows + kBinRows - 1) / kBinRows;
  out->assign(static_cast<size_t>(bins) * 9 * kBinRows, Scalar(0));
  for (int32_t r = 0; r < rows; ++r)
    copyBlockLaneMinor(blocks + 9 * static_cast<size_t>(r), &(*out)[kernels::laneBlockOffset(r / kBinRows, r % kBinRows)]);
}

template struct BinBcsrMatrix<float>;
template struct BinBcsrMatrix<double>;
template void buildBinBcsr(const BlockSparseMatrix<double>&, BinBcsrMatrix<double>*);
template void buildBinBcsr(const BlockSparseMatrix<double>&, BinBcsrMatrix<float>*);
template void buildBinBcsr(const BlockSparseMatrix<float>&, BinBcsrMatrix<float>*);
template void refreshBinBcsrValues(const BlockSparseMatrix<double>&, BinBcsrMatrix<double>*);
template void refreshBinBcsrValues(const BlockSparseMatrix<double>&, BinBcsrMatrix<float>*);
template void refreshBinBcsrValues(const BlockSparseMatrix<float>&, BinBcsrMatrix<float>*);
template void binnedInverseDiagonal(const BlockSparseMatrix<double>&, Array<float>*);
template void binnedInverseDiagonal(const BlockSparseMatrix<double>&, Array<double>*);
template void binnedBlocks(const double*, int32_t, Array<float>*);
template void binnedBlocks(const double*, int32_t, Array<double>*);

}  // namespace vp

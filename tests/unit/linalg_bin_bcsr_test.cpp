// BIN-BCSR (the GPU's layout) built from BCSR and multiplied by the CPU loop that reads its
// arrays exactly as the CUDA kernel does: bit for bit the BCSR product.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstring>
#include <random>

#include "deform/bb_multi_index.h"
#include "deform/deformable_body.h"
#include "geometry/box_tet_mesh.h"
#include "linalg/bin_bcsr_matrix.h"
#include "random_values.h"

namespace vp {
namespace {

using kernels::kBinRows;

// The pattern a deformable of this degree assembles (every pair of nodes sharing an element).
template <class Scalar>
BlockSparseMatrix<Scalar> elementPatternOfDegree(int degree) {
  DeformableDesc desc;
  desc.degree = degree;
  desc.mesh = makeBoxTetMesh({3, 2, 2}, Vec3(3, 2, 2), Vec3::Zero());
  std::unique_ptr<DeformableBody> body;
  EXPECT_EQ(DeformableBody::create(desc, &body), Status::Ok) << lastError();
  BlockSparseMatrix<Scalar> m;
  Array<int32_t> scatter;
  buildElementPattern(body->nodeCount(), body->elementNodes().data(), body->elementCount(), bbNodeCount(degree), &m,
                      &scatter);
  return m;
}

template <class Scalar>
void fillRandom(BlockSparseMatrix<Scalar>& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  for (Scalar& v : m.values) v = static_cast<Scalar>(u(rng));
}

using testing_values::randomValues;

bool bitwiseEqual(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

template <class Scalar>
void expectSameProducts(const BlockSparseMatrix<Scalar>& bcsr, const BinBcsrMatrix<Scalar>& bin) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const std::vector<double> x = randomValues<double>(3 * static_cast<int64_t>(bcsr.blockRows), 11);
  std::vector<double> y(x.size(), -7.0), yBin(x.size(), 7.0);
  bcsr.multiply(*tasks, x.data(), y.data());
  bin.multiply(*tasks, x.data(), yBin.data());
  EXPECT_TRUE(bitwiseEqual(y, yBin));
}

template <class Scalar>
void checkDegree(int degree) {
  BlockSparseMatrix<Scalar> m = elementPatternOfDegree<Scalar>(degree);
  ASSERT_NE(m.blockRows % kBinRows, 0) << "the last bin should be padded";
  fillRandom(m, 5 + degree);
  BinBcsrMatrix<Scalar> bin;
  buildBinBcsr(m, &bin);
  EXPECT_EQ(bin.bins(), (m.blockRows + kBinRows - 1) / kBinRows);
  int64_t stored = 0;
  for (int32_t c : bin.columns) stored += c >= 0;
  EXPECT_EQ(stored + m.blockRows, m.blockCount()) << "every off-diagonal block stored once, diagonals apart";
  expectSameProducts(m, bin);
  // New values in the same pattern: a refresh gives the new product, bit for bit.
  fillRandom(m, 99);
  refreshBinBcsrValues(m, &bin);
  expectSameProducts(m, bin);
}

TEST(BinBcsr, LinearQuadraticAndCubicPatternsMultiplyLikeBcsrBitForBit) {
  for (int degree = 1; degree <= 3; ++degree) {
    SCOPED_TRACE(degree);
    checkDegree<double>(degree);
    checkDegree<float>(degree);
  }
}

// Rows with no blocks, rows with only a diagonal, a row with no diagonal, and rows whose
// diagonal comes first, in the middle and last, across two bins.
TEST(BinBcsr, EmptyRowsMissingDiagonalsAndPaddedBinsMultiplyLikeBcsr) {
  const int32_t rows = kBinRows + 5;
  BlockSparseMatrix<double> m;
  m.blockRows = rows;
  m.rowStart.assign(rows + 1, 0);
  for (int32_t r = 0; r < rows; ++r) {
    std::vector<int32_t> cols;
    const auto add = [&](std::initializer_list<int32_t> list) {
      for (int32_t c : list) cols.push_back(c);
    };
    switch (r % 5) {
      case 0: break;                               // empty
      case 1: add({r}); break;                     // diagonal only
      case 2:                                      // diagonal last, or no diagonal ((r + 7) % rows != r)
        (r / 5) % 2 == 0 ? add({0, r}) : add({0, (r + 7) % rows});
        break;
      case 3: add({r, r + 1}); break;              // diagonal first
      default: add({0, r, rows - 1}); break;       // diagonal in the middle
    }
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    for (int32_t c : cols) m.columns.push_back(c);
    m.rowStart[r + 1] = static_cast<int32_t>(m.columns.size());
  }
  m.values.assign(9 * m.columns.size(), 0.0);
  m.diagonal.resize(rows);
  for (int32_t r = 0; r < rows; ++r) m.diagonal[r] = m.find(r, r);
  fillRandom(m, 3);
  BinBcsrMatrix<double> bin;
  buildBinBcsr(m, &bin);
  EXPECT_EQ(bin.diagonalPosition[0], -1);
  EXPECT_EQ(bin.diagonalPosition[1], 0);
  EXPECT_EQ(bin.diagonalPosition[2], 1);
  EXPECT_EQ(bin.diagonalPosition[7], -1);
  EXPECT_EQ(bin.diagonalPosition[3], 0);
  EXPECT_EQ(bin.diagonalPosition[4], 1);
  expectSameProducts(m, bin);
}

TEST(BinBcsr, BlockJacobiRowAppliesTheInverseDiagonalBlocks) {
  BlockSparseMatrix<double> m = elementPatternOfDegree<double>(1);
  fillRandom(m, 8);
  for (int32_t r = 0; r < m.blockRows; ++r)  // diagonally dominant: every block invertible
    for (int i = 0; i < 3; ++i) m.values[9 * static_cast<size_t>(m.diagonal[r]) + 4 * i] += 4.0;
  Array<double> inverse;
  binnedInverseDiagonal(m, &inverse);
  const std::vector<double> r = randomValues<double>(3 * static_cast<int64_t>(m.blockRows), 4);
  std::vector<double> z(r.size());
  for (int32_t row = 0; row < m.blockRows; ++row) kernels::blockJacobiRow(row, inverse.data(), r.data(), z.data());
  using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  for (int32_t row = 0; row < m.blockRows; ++row) {
    const Mat3R d = Eigen::Map<const Mat3R>(&m.values[9 * static_cast<size_t>(m.diagonal[row])]);
    const Eigen::Vector3d back = d * Eigen::Map<const Eigen::Vector3d>(&z[3 * static_cast<size_t>(row)]);
    // D (D^-1 r) = r to a few ulps of |D||D^-1||r| (the blocks' condition is near 1).
    EXPECT_LT((back - Eigen::Map<const Eigen::Vector3d>(&r[3 * static_cast<size_t>(row)])).norm(), 1e-13);
  }
}

}  // namespace
}  // namespace vp

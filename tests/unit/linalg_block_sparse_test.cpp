#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "linalg/block_sparse_matrix.h"

namespace vp {
namespace {

// Two tets sharing a face, plus an isolated node 5: pattern, scatter and multiply against a
// dense reference.
TEST(BlockSparseMatrix, PatternScatterAndMultiplyMatchDense) {
  const int32_t elements[8] = {0, 1, 2, 3, 1, 2, 3, 4};
  BlockSparseMatrix<double> m;
  Array<int32_t> scatter;
  buildElementPattern(6, elements, 2, 4, &m, &scatter);
  EXPECT_EQ(m.blockRows, 6);
  // Node 0 couples with 0..3, node 4 with 1..4, nodes 1..3 with 0..4, node 5 only itself.
  EXPECT_EQ(m.blockCount(), 4 + 4 + 3 * 5 + 1);
  EXPECT_EQ(m.find(0, 4), -1);
  EXPECT_GE(m.find(1, 4), 0);
  for (int32_t r = 0; r < 6; ++r) EXPECT_EQ(m.columns[m.diagonal[r]], r);

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(18, 18);
  for (int e = 0; e < 2; ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int32_t k = scatter[(e * 4 + a) * 4 + b];
        ASSERT_EQ(k, m.find(elements[e * 4 + a], elements[e * 4 + b]));
        for (int i = 0; i < 9; ++i) {
          const double v = u(rng);
          m.values[9 * k + i] += v;
          dense(3 * elements[e * 4 + a] + i / 3, 3 * elements[e * 4 + b] + i % 3) += v;
        }
      }
  Eigen::VectorXd x = Eigen::VectorXd::Random(18), y(18);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  m.multiply(*tasks, x.data(), y.data());
  EXPECT_LT((y - dense * x).norm(), 1e-12 * (dense * x).norm());
}

}  // namespace
}  // namespace vp

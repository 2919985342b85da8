// The block-wise rotated BB stiffness from rotated gradient pairs equals R K_e Rᵀ of the
// analytic rest stiffness, for every degree.
#include "deform/bb_rotated_stiffness.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "deform/bb_element_matrices.h"
#include "deform/bb_multi_index.h"
#include "deform/corotated_element.h"
#include "deform_test_util.h"

namespace vp {
namespace {

TEST(DeformBBRotatedStiffness, GradientPairsReproduceTheRotatedRestStiffness) {
  std::mt19937 rng(17);
  const double lambda = 3.1e5, mu = 1.7e5, scale = 0.37;
  for (int degree = 1; degree <= 3; ++degree) {
    const BBStiffnessTerms terms = bbStiffnessTerms(degree);
    const int N = bbNodeCount(degree), dim = 3 * N;
    for (int trial = 0; trial < 3; ++trial) {
      double corners[12], grad[12], volume;
      deform_test::randomTet(rng, corners);
      ASSERT_EQ(bbBarycentricGradients(corners, grad, &volume), Status::Ok);
      std::vector<double> K(static_cast<size_t>(dim * dim)), rotated(K.size());
      ASSERT_EQ(bbStiffnessMatrix(degree, corners, lambda, mu, K.data()), Status::Ok);
      const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R = deform_test::randomRotation(rng);
      corotatedStiffness(N, K.data(), R.data(), rotated.data());
      double pairs[144];
      kernels::bbRotatedGradientPairs(degree, R.data(), grad, volume, lambda, mu, scale, pairs);
      double worst = 0.0, largest = 0.0;
      for (int a = 0; a < N; ++a)
        for (int b = 0; b < N; ++b) {
          double block[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
          kernels::addBBRotatedBlock(terms.view(), pairs, N, a, b, block);
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
              const double expected = scale * rotated[(3 * a + i) * dim + 3 * b + j];
              worst = std::max(worst, std::abs(block[3 * i + j] - expected));
              largest = std::max(largest, std::abs(expected));
            }
        }
      EXPECT_LT(worst, 1e-12 * largest) << "degree " << degree;
    }
  }
}

// The rest stiffness applied without storing it (kernels::bbStiffnessApply over
// bbStiffnessStructure) against the stored matrix times u: the same sums regrouped, so equal to
// round-off of the largest term, |K| |u| times a few hundred ulps (the 1e-13).
TEST(DeformBBRotatedStiffness, UnstoredApplyEqualsTheRestStiffnessMatrix) {
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double lambda = 3.1e5, mu = 1.7e5;
  for (int degree = 1; degree <= 3; ++degree) {
    const BBStiffnessStructure structure = bbStiffnessStructure(degree);
    const int N = bbNodeCount(degree), dim = 3 * N;
    for (int trial = 0; trial < 5; ++trial) {
      double corners[12], grad[12], volume;
      deform_test::randomTet(rng, corners);
      ASSERT_EQ(bbBarycentricGradients(corners, grad, &volume), Status::Ok);
      std::vector<double> K(static_cast<size_t>(dim * dim)), u(dim), Ku(dim);
      ASSERT_EQ(bbStiffnessMatrix(degree, corners, lambda, mu, K.data()), Status::Ok);
      for (double& v : u) v = uniform(rng);
      kernels::bbStiffnessApply(degree, structure.view(), grad, volume, lambda, mu, u.data(), Ku.data());
      double worst = 0.0, scale = 0.0;
      for (int i = 0; i < dim; ++i) {
        double expected = 0.0, magnitude = 0.0;
        for (int j = 0; j < dim; ++j) {
          expected += K[i * dim + j] * u[j];
          magnitude += std::abs(K[i * dim + j] * u[j]);
        }
        worst = std::max(worst, std::abs(Ku[i] - expected));
        scale = std::max(scale, magnitude);
      }
      EXPECT_LT(worst, 1e-13 * scale) << "degree " << degree;
      EXPECT_GT(scale, 0.0);
    }
  }
}

}  // namespace
}  // namespace vp

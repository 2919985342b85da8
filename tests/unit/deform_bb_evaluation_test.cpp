// Evaluation of BB fields and degree elevation.
#include "deform/bb_evaluation.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "deform/bb_element_matrices.h"
#include "deform/bb_multi_index.h"
#include "deform_test_util.h"

namespace vp {
namespace {

using deform_test::randomBary;

void randomCoeffs(std::mt19937& rng, int degree, double* c) {
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 3 * bbNodeCount(degree); ++i) c[i] = u(rng);
}

TEST(DeformBBEvaluation, PartitionOfUnityAndInterpolationAtVertices) {
  std::mt19937 rng(31);
  for (int n = 1; n <= 3; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      double bary[4], basis[kBBMaxNodes];
      randomBary(rng, bary);
      bbBasis(n, bary, basis);
      double sum = 0.0;
      for (int k = 0; k < bbNodeCount(n); ++k) {
        EXPECT_GE(basis[k], 0.0);
        sum += basis[k];
      }
      EXPECT_NEAR(sum, 1.0, 1e-15 * 8);  // ≤ 20 terms of size ≤ 1
    }
    // A BB field interpolates its vertex control points (and only those).
    double c[3 * kBBMaxNodes];
    randomCoeffs(rng, n, c);
    for (int v = 0; v < 4; ++v) {
      double bary[4] = {0, 0, 0, 0};
      bary[v] = 1.0;
      double value[3];
      bbEvaluate(n, c, bary, value);
      for (int a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(value[a], c[3 * v + a]);
    }
  }
}

TEST(DeformBBEvaluation, ReproducesAffineFieldsFromRestNodePositions) {
  std::mt19937 rng(32);
  double corners[12];
  deform_test::randomTet(rng, corners);
  const Eigen::Matrix3d f = deform_test::randomMatrix(rng);
  const Eigen::Vector3d t(0.3, -1.2, 2.0);
  double baryGrad[12], volume;
  ASSERT_EQ(bbBarycentricGradients(corners, baryGrad, &volume), Status::Ok);
  for (int n = 1; n <= 3; ++n) {
    double nodes[3 * kBBMaxNodes], c[3 * kBBMaxNodes];
    ASSERT_EQ(bbRestNodePositions(n, corners, nodes), Status::Ok);
    for (int k = 0; k < bbNodeCount(n); ++k)
      Eigen::Map<Eigen::Vector3d>(c + 3 * k) = f * Eigen::Map<Eigen::Vector3d>(nodes + 3 * k) + t;
    double bary[4];
    randomBary(rng, bary);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) x += bary[i] * Eigen::Map<const Eigen::Vector3d>(corners + 3 * i);
    Eigen::Vector3d value;
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> grad;
    bbEvaluate(n, c, bary, value.data());
    bbEvaluateGradient(n, c, bary, baryGrad, grad.data());
    // Coordinates up to ~10, so 1e-12 absolute is a few hundred ulps.
    EXPECT_LT((value - (f * x + t)).norm(), 1e-12) << "n=" << n;
    EXPECT_LT((Eigen::Matrix3d(grad) - f).norm(), 1e-12) << "n=" << n;
  }
}

TEST(DeformBBEvaluation, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(33);
  double corners[12];
  deform_test::randomTet(rng, corners);
  double baryGrad[12], volume;
  ASSERT_EQ(bbBarycentricGradients(corners, baryGrad, &volume), Status::Ok);
  for (int n = 1; n <= 3; ++n) {
    double c[3 * kBBMaxNodes];
    randomCoeffs(rng, n, c);
    double bary[4];
    randomBary(rng, bary);
    double grad[9];
    bbEvaluateGradient(n, c, bary, baryGrad, grad);
    // Move X by ±h along axis j: λ moves by ±h ∇λ_c[j]. Central differences of a cubic
    // have error h²/6·|f'''| ≈ 1e-9 for h = 1e-4; round-off ≈ 1e-16/h = 1e-12.
    const double h = 1e-4;
    for (int j = 0; j < 3; ++j) {
      double plus[4], minus[4], vp3[3], vm3[3];
      for (int c4 = 0; c4 < 4; ++c4) {
        plus[c4] = bary[c4] + h * baryGrad[3 * c4 + j];
        minus[c4] = bary[c4] - h * baryGrad[3 * c4 + j];
      }
      bbEvaluate(n, c, plus, vp3);
      bbEvaluate(n, c, minus, vm3);
      for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(grad[3 * a + j], (vp3[a] - vm3[a]) / (2 * h), 1e-6) << "n=" << n;
    }
  }
}

TEST(DeformBBEvaluation, ElevationReproducesTheLowerDegreeField) {
  std::mt19937 rng(34);
  double corners[12];
  deform_test::randomTet(rng, corners);
  double baryGrad[12], volume;
  ASSERT_EQ(bbBarycentricGradients(corners, baryGrad, &volume), Status::Ok);
  for (int n = 1; n <= 2; ++n) {
    double coarse[3 * kBBMaxNodes], fine[3 * kBBMaxNodes];
    randomCoeffs(rng, n, coarse);
    bbElevate(n, coarse, fine);
    for (int trial = 0; trial < 50; ++trial) {
      double bary[4], a[3], b[3], ga[9], gb[9];
      randomBary(rng, bary);
      bbEvaluate(n, coarse, bary, a);
      bbEvaluate(n + 1, fine, bary, b);
      bbEvaluateGradient(n, coarse, bary, baryGrad, ga);
      bbEvaluateGradient(n + 1, fine, bary, baryGrad, gb);
      // Same polynomial, different sums of ≤ 20 terms of size ≤ 2: round-off only.
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-13) << "n=" << n;
      for (int k = 0; k < 9; ++k) EXPECT_NEAR(ga[k], gb[k], 1e-11) << "n=" << n;
    }
  }
  // Two steps, 1 -> 3: the vertex nodes are untouched, the linear field is reproduced.
  double linear[12], quadratic[30], cubic[60];
  randomCoeffs(rng, 1, linear);
  bbElevate(1, linear, quadratic);
  bbElevate(2, quadratic, cubic);
  for (int i = 0; i < 12; ++i) EXPECT_DOUBLE_EQ(cubic[i], linear[i]);
  double bary[4], a[3], b[3];
  randomBary(rng, bary);
  bbEvaluate(1, linear, bary, a);
  bbEvaluate(3, cubic, bary, b);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-13);
}

TEST(DeformBBEvaluation, ElevationRowsArePartitionsOfUnityOnTheSameSubsimplex) {
  for (int n = 1; n <= 2; ++n) {
    BBElevationRow rows[kBBMaxNodes];
    ASSERT_EQ(bbElevationRows(n, rows), Status::Ok);
    const BBMultiIndex* fine = bbMultiIndices(n + 1);
    const BBMultiIndex* coarse = bbMultiIndices(n);
    for (int k = 0; k < bbNodeCount(n + 1); ++k) {
      double sum = 0.0;
      for (int m = 0; m < rows[k].count; ++m) {
        sum += rows[k].weight[m];
        // A coarse node feeding fine node k lies on k's vertex/edge/face: that is what
        // makes per-element prolongation consistent between neighbouring tets.
        for (int i = 0; i < 4; ++i) {
          if (fine[k].a[i] == 0) {
            EXPECT_EQ(coarse[rows[k].node[m]].a[i], 0);
          }
        }
      }
      EXPECT_DOUBLE_EQ(sum, 1.0);
    }
  }
  BBElevationRow rows[kBBMaxNodes];
  EXPECT_EQ(bbElevationRows(3, rows), Status::InvalidArgument);
}

}  // namespace
}  // namespace vp

// Rotation extraction: proper rotations for every F, including degenerate and inverted ones.
#include "gpu_kernels/polar_kernels.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <random>

#include "deform_test_util.h"
#include "random_values.h"

namespace vp {
namespace {

using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using deform_test::randomMatrix;
using deform_test::randomRotation;
using kernels::polarRotationIterative;
using kernels::polarRotationSvd;
using kernels::quaternionFromRotation;
using kernels::rotationFromQuaternion;

// Irving's rotation through Eigen's two-sided Jacobi SVD: an independent reference for the
// hand-written kernel.
Eigen::Matrix3d eigenIrvingRotation(const Eigen::Matrix3d& f) {
  const Eigen::JacobiSVD<Eigen::Matrix3d, Eigen::NoQRPreconditioner> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  if (u.determinant() * svd.matrixV().determinant() < 0.0) u.col(2) = -u.col(2);
  return u * svd.matrixV().transpose();
}

Eigen::Matrix3d svdRotation(const Eigen::Matrix3d& f) {
  const Mat3R in = f;
  Mat3R r;
  EXPECT_TRUE(polarRotationSvd(in.data(), r.data()));
  return r;
}

// Orthonormality and det to 1e-14: a product of exactly orthogonal factors carries only a
// few ulps of error per entry.
void expectProperRotation(const Eigen::Matrix3d& r, const char* what) {
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 1e-14) << what;
  EXPECT_NEAR(r.determinant(), 1.0, 1e-14) << what;
}

TEST(DeformPolarDecomposition, RandomMatricesGiveTheRotationalPolarFactor) {
  std::mt19937 rng(41);
  int inverted = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix3d f = randomMatrix(rng, -2.0, 2.0);
    const Eigen::Matrix3d r = svdRotation(f);
    expectProperRotation(r, "random F");
    // S = Rᵀ F must be symmetric (F = R S); for det F > 0 also positive definite, for
    // det F < 0 with exactly one negative eigenvalue, the smallest in magnitude.
    const Eigen::Matrix3d s = r.transpose() * f;
    EXPECT_LT((s - s.transpose()).norm(), 1e-13 * f.norm());
    const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(
                                   0.5 * (s + s.transpose())).eigenvalues();
    const Eigen::Vector3d sigma = Eigen::JacobiSVD<Eigen::Matrix3d>(f).singularValues();
    if (f.determinant() > 0.0) {
      EXPECT_GT(ev.minCoeff(), -1e-13);
    } else {
      ++inverted;
      EXPECT_LT(ev[0], 0.0);
      EXPECT_NEAR(ev[0], -sigma[2], 1e-12);
      EXPECT_GE(ev[1], -1e-13);
    }
  }
  EXPECT_GT(inverted, 50);  // the sample really exercised inverted F
}

// Where the rotation is unique and well conditioned (σ1 + σ2 bounded away from 0), the kernel
// and Eigen agree to round-off amplified by that conditioning: 1e-13 / (σ1 + σ2) per entry.
TEST(DeformPolarDecomposition, AgreesWithEigensSvd) {
  std::mt19937 rng(48);
  int compared = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Matrix3d f = randomMatrix(rng, -2.0, 2.0);
    const Eigen::Vector3d sigma = Eigen::JacobiSVD<Eigen::Matrix3d>(f).singularValues();
    const double conditioning = (sigma[1] + sigma[2]) / sigma[0];
    if (conditioning < 1e-2) continue;
    ++compared;
    const Eigen::Matrix3d difference = svdRotation(f) - eigenIrvingRotation(f);
    EXPECT_LT(difference.cwiseAbs().maxCoeff(), 1e-13 / conditioning) << "trial " << trial;
  }
  EXPECT_GT(compared, 300);
}

// The SVD works on F scaled to a largest entry of order 1: the rotation of F times a power of
// two is the same bits, and F of any finite magnitude gives a proper rotation (its squared
// column norms would overflow past 1e154 and underflow below 1e-154 unscaled).
TEST(DeformPolarDecomposition, SvdRotationDoesNotDependOnFsMagnitude) {
  std::mt19937 rng(49);
  for (int trial = 0; trial < 100; ++trial) {
    const Mat3R f = randomMatrix(rng, -2.0, 2.0);
    Mat3R reference;
    ASSERT_TRUE(polarRotationSvd(f.data(), reference.data()));
    for (int power : {-1000, -600, -1, 1, 600, 1000}) {
      const Mat3R scaled = f * std::ldexp(1.0, power);
      Mat3R r;
      ASSERT_TRUE(polarRotationSvd(scaled.data(), r.data()));
      EXPECT_EQ(std::memcmp(r.data(), reference.data(), sizeof(double) * 9), 0) << "2^" << power;
    }
    for (double magnitude : {1e-300, 1e300}) {
      const Mat3R scaled = f * magnitude;
      Mat3R r;
      ASSERT_TRUE(polarRotationSvd(scaled.data(), r.data()));
      expectProperRotation(r, "extreme magnitude");
      EXPECT_LT((r - reference).cwiseAbs().maxCoeff(), 1e-12) << magnitude;
    }
  }
}

TEST(DeformPolarDecomposition, PureRotationIsReturnedUnchanged) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d q = randomRotation(rng);
    EXPECT_LT((svdRotation(q) - q).norm(), 1e-14);
  }
}

TEST(DeformPolarDecomposition, DegenerateAndInvertedMatricesStayProper) {
  std::mt19937 rng(43);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d u = randomRotation(rng), v = randomRotation(rng);
    auto make = [&](double a, double b, double c) {
      return Eigen::Matrix3d(u * Eigen::Vector3d(a, b, c).asDiagonal() * v.transpose());
    };
    // Near-singular and rank 2: the rotation is unique (U Vᵀ) and must be found.
    EXPECT_LT((svdRotation(make(1.0, 0.5, 1e-12)) - u * v.transpose()).norm(), 1e-12);
    EXPECT_LT((svdRotation(make(1.0, 0.5, 0.0)) - u * v.transpose()).norm(), 1e-12);
    // Rank 1 and zero: any rotation is a valid answer; it must still be one.
    expectProperRotation(svdRotation(make(2.0, 0.0, 0.0)), "rank 1");
    expectProperRotation(svdRotation(Eigen::Matrix3d::Zero()), "zero");
    // Inverted: squashed through the third axis. Irving's choice puts the reflection on the
    // smallest singular direction, so R = U Vᵀ again, not a reflection.
    EXPECT_LT((svdRotation(make(1.0, 0.8, -0.3)) - u * v.transpose()).norm(), 1e-12);
    // Fully inverted (−Q): every singular value is 1; any proper rotation is acceptable.
    expectProperRotation(svdRotation(-u), "point reflection");
    // Inverted and rank 2 at once (flat and flipped).
    expectProperRotation(svdRotation(make(-1.0, 0.5, 0.0)), "rank 2 inverted");
  }
}

TEST(DeformPolarDecomposition, NonFiniteInputGivesIdentityAndFalse) {
  double f[9] = {1, 0, 0, 0, 1, 0, 0, 0, NAN};
  double r[9];
  EXPECT_FALSE(polarRotationSvd(f, r));
  for (int i = 0; i < 9; ++i) EXPECT_EQ(r[i], i % 4 == 0 ? 1.0 : 0.0);
  double q[4] = {1, 0, 0, 0};
  EXPECT_EQ(polarRotationIterative(f, q, r, 10, 1e-12), -1);
}

TEST(DeformPolarDecomposition, IterativeMatchesSvdWhenWarmStarted) {
  std::mt19937 rng(44);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 200; ++trial) {
    // F = Q S with a moderate stretch, det of either sign.
    const Eigen::Matrix3d q = randomRotation(rng);
    Eigen::Matrix3d s = Eigen::Matrix3d::Identity() + 0.3 * randomMatrix(rng);
    s = 0.5 * (s + s.transpose());
    if (trial % 4 == 0) s.col(2) *= -1.0;  // inverted elements too
    const Mat3R f = q * s;
    const Eigen::Matrix3d reference = svdRotation(f);
    // Warm start: last frame's rotation, off by up to ~0.3 rad about a random axis.
    const Eigen::Vector3d axis = testing_values::randomVector(normal, rng).normalized();
    const Eigen::Quaterniond start(Eigen::AngleAxisd(0.3, axis) * reference);
    double quat[4] = {start.w(), start.x(), start.y(), start.z()};
    Mat3R r;
    // Inverted F (every 4th) take the SVD path and report 0 iterations.
    const int iterations = polarRotationIterative(f.data(), quat, r.data(), 50, 1e-12);
    EXPECT_LT(iterations, 50);
    if (trial % 4 == 0) {
      EXPECT_EQ(iterations, 0);
    }
    expectProperRotation(r, "iterative");
    // Converged to ω < 1e-12: the angle to the optimum is ~1e-12 times cond(S); 1e-9 holds.
    EXPECT_LT((Eigen::Matrix3d(r) - reference).norm(), 1e-9) << "trial " << trial;
    EXPECT_NEAR(Eigen::Vector4d(quat[0], quat[1], quat[2], quat[3]).norm(), 1.0, 1e-14);
  }
}

TEST(DeformPolarDecomposition, IterativeConvergesFromAnyStartForNonInvertedF) {
  std::mt19937 rng(47);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 200; ++trial) {
    Mat3R f = randomMatrix(rng, -1.0, 1.0);
    if (f.determinant() < 0.0) f = -f;
    const Eigen::Matrix3d reference = svdRotation(f);
    // Up to 3.1 rad from the answer, i.e. nearly the opposite rotation.
    const double angle = 3.1 * (trial + 1) / 200.0;
    const Eigen::Vector3d axis = testing_values::randomVector(normal, rng).normalized();
    const Eigen::Quaterniond start(Eigen::AngleAxisd(angle, axis) * reference);
    double quat[4] = {start.w(), start.x(), start.y(), start.z()};
    Mat3R r;
    const int iterations = polarRotationIterative(f.data(), quat, r.data(), 100, 1e-12);
    EXPECT_GT(iterations, 0);
    EXPECT_LT(iterations, 100);
    // Random F include ill-conditioned ones (σ3 ~ 1e-2): the answer's sensitivity is
    // ~1/(σ2 + σ3), so 1e-8 rather than the 1e-12 of the step tolerance.
    EXPECT_LT((Eigen::Matrix3d(r) - reference).norm(), 1e-8) << "trial " << trial;
  }
}

TEST(DeformPolarDecomposition, IterativeStaysARotationWhenStoppedEarlyOrDegenerate) {
  std::mt19937 rng(45);
  const Mat3R zero = Mat3R::Zero();
  const Eigen::Quaterniond start(randomRotation(rng));
  double quat[4] = {start.w(), start.x(), start.y(), start.z()};
  Mat3R r;
  // det F = 0: answered by the SVD (0 iterations); any rotation is valid for F = 0.
  EXPECT_EQ(polarRotationIterative(zero.data(), quat, r.data(), 20, 1e-12), 0);
  expectProperRotation(r, "zero F");
  Mat3R fromQuat;
  rotationFromQuaternion(quat, fromQuat.data());
  EXPECT_LT((fromQuat - r).norm(), 1e-14);  // quat and R describe the same rotation
  Mat3R f = randomMatrix(rng, -3.0, 3.0);
  if (f.determinant() < 0.0) f = -f;  // the iteration proper only runs for det F > 0
  double fresh[4] = {1, 0, 0, 0};
  EXPECT_EQ(polarRotationIterative(f.data(), fresh, r.data(), 1, 0.0), 1);
  expectProperRotation(r, "one iteration");
}

TEST(DeformPolarDecomposition, QuaternionHelpersRoundTrip) {
  std::mt19937 rng(46);
  const Mat3R q = randomRotation(rng);
  double quat[4];
  Mat3R back;
  quaternionFromRotation(q.data(), quat);
  rotationFromQuaternion(quat, back.data());
  EXPECT_LT((back - q).norm(), 1e-14);
}

}  // namespace
}  // namespace vp

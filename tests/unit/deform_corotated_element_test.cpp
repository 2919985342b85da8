// Element kinematics and corotation: the volume-averaged deformation gradient, and the
// corotated force and stiffness for degree 1, 2, 3.
#include "deform/corotated_element.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "deform/bb_element_matrices.h"
#include "deform/bb_evaluation.h"
#include "deform/bb_multi_index.h"
#include "deform/deformation_gradient.h"
#include "gpu_kernels/bb_element_kernels.h"
#include "gpu_kernels/linear_tet_kernels.h"
#include "gpu_kernels/polar_kernels.h"
#include "deform_test_util.h"

namespace vp {
namespace {

using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using deform_test::randomRotation;

struct Element {
  int degree;
  int nodes;
  double corners[12];
  double baryGrad[12];
  double volume;
  VectorXd rest;                   // N x 3
  std::vector<double> stiffness;   // 3N x 3N row-major
  MatrixXd k;                      // the same, for reference arithmetic
};

Element makeElement(std::mt19937& rng, int degree) {
  Element e;
  e.degree = degree;
  e.nodes = bbNodeCount(degree);
  deform_test::randomTet(rng, e.corners);
  EXPECT_EQ(bbBarycentricGradients(e.corners, e.baryGrad, &e.volume), Status::Ok);
  e.rest.resize(3 * e.nodes);
  EXPECT_EQ(bbRestNodePositions(degree, e.corners, e.rest.data()), Status::Ok);
  const int d = 3 * e.nodes;
  e.stiffness.resize(d * d);
  EXPECT_EQ(bbStiffnessMatrix(degree, e.corners, 2.0e5, 8.0e4, e.stiffness.data()), Status::Ok);
  e.k = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      e.stiffness.data(), d, d);
  return e;
}

VectorXd affine(const Element& e, const Eigen::Matrix3d& f, const Eigen::Vector3d& t) {
  VectorXd x(e.rest.size());
  for (int k = 0; k < e.nodes; ++k) x.segment<3>(3 * k) = f * e.rest.segment<3>(3 * k) + t;
  return x;
}

Eigen::Matrix3d averageF(const Element& e, const VectorXd& x) {
  Mat3R f;
  bbAverageDeformationGradient(e.degree, x.data(), e.baryGrad, f.data());
  return f;
}

Eigen::Matrix3d rotationOf(const Element& e, const VectorXd& x) {
  const Mat3R f = averageF(e, x);
  Mat3R r;
  EXPECT_TRUE(kernels::polarRotationSvd(f.data(), r.data()));
  return r;
}

VectorXd force(const Element& e, const VectorXd& x, const Eigen::Matrix3d& r) {
  const Mat3R rr = r;
  VectorXd f(x.size());
  corotatedForce(e.nodes, e.stiffness.data(), e.rest.data(), x.data(), rr.data(), f.data());
  return f;
}

// ---- deformation gradient ----------------------------------------------------------------

TEST(DeformDeformationGradient, ExactForAffinePositionsEveryDegree) {
  std::mt19937 rng(51);
  for (int n = 1; n <= 3; ++n)
    for (int trial = 0; trial < 10; ++trial) {
      const Element e = makeElement(rng, n);
      const Eigen::Matrix3d f = deform_test::randomMatrix(rng, -2.0, 2.0);
      const Eigen::Matrix3d got = averageF(e, affine(e, f, Eigen::Vector3d(4, -3, 7)));
      // Positions ~10, gradients ~1/h with h ≥ 0.2: round-off ≈ 1e-15·10·5·(20 terms).
      EXPECT_LT((got - f).norm(), 1e-12) << "n=" << n;
    }
}

TEST(DeformDeformationGradient, IsTheVolumeAverageOfTheFieldGradient) {
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 1; n <= 3; ++n) {
    const Element e = makeElement(rng, n);
    VectorXd x(3 * e.nodes);
    for (int i = 0; i < x.size(); ++i) x[i] = e.rest[i] + u(rng);  // not affine
    // ∇x has degree n−1 ≤ 2; the 4-point rule (Keast/Hammer, points at a = 0.5854…,
    // b = 0.1381…) integrates degree 2 exactly.
    const double a = 0.5854101966249685, b = 0.1381966011250105;
    Eigen::Matrix3d mean = Eigen::Matrix3d::Zero();
    for (int p = 0; p < 4; ++p) {
      double bary[4] = {b, b, b, b};
      bary[p] = a;
      Mat3R g;
      bbEvaluateGradient(n, x.data(), bary, e.baryGrad, g.data());
      mean += 0.25 * Eigen::Matrix3d(g);
    }
    EXPECT_LT((averageF(e, x) - mean).norm(), 1e-12 * mean.norm()) << "n=" << n;
    if (n == 1) {
      // Linear element: the classic Ds Dm⁻¹.
      Eigen::Matrix3d ds, dm;
      for (int k = 1; k < 4; ++k) {
        ds.col(k - 1) = x.segment<3>(3 * k) - x.segment<3>(0);
        dm.col(k - 1) = e.rest.segment<3>(3 * k) - e.rest.segment<3>(0);
      }
      EXPECT_LT((averageF(e, x) - ds * dm.inverse()).norm(), 1e-12 * mean.norm());
    }
  }
}

// BB control points of the field g: interpolation at the equispaced lattice X_β (the rest
// node positions), exact whenever g is a polynomial of degree <= n.
template <typename Field>
VectorXd interpolate(const Element& e, Field g) {
  const BBMultiIndex* nodes = bbMultiIndices(e.degree);
  MatrixXd a(e.nodes, e.nodes);
  MatrixXd values(e.nodes, 3);
  for (int b = 0; b < e.nodes; ++b) {
    double bary[4], basis[kBBMaxNodes];
    for (int i = 0; i < 4; ++i) bary[i] = static_cast<double>(nodes[b].a[i]) / e.degree;
    bbBasis(e.degree, bary, basis);
    for (int k = 0; k < e.nodes; ++k) a(b, k) = basis[k];
    values.row(b) = g(Eigen::Vector3d(e.rest.segment<3>(3 * b))).transpose();
  }
  const MatrixXd c = a.partialPivLu().solve(values);
  VectorXd x(3 * e.nodes);
  for (int k = 0; k < e.nodes; ++k) x.segment<3>(3 * k) = c.row(k).transpose();
  return x;
}

TEST(DeformDeformationGradient, TorsionRotatesByTheMeanTwistAngle) {
  // A bar twisted about the z axis by k radians per length, then rigidly rotated by Q. For
  // an element centred on the axis at height Z̄ = 10, with δ = Z − Z̄,
  //   x = Q R_z(k Z̄) (X + k δ (e_z × X)) + O((kh)² h),
  // which is quadratic, hence exactly representable for n >= 2. Its infinitesimal rotation
  // k(−X/2, −Y/2, δ) averages to zero over the element, so the element rotation must be
  // Q R_z(k Z̄) up to O((k h)²) ≈ 4e-4 (h ≈ 4); the signal k Z̄ is 0.05, and a rotation
  // sampled at a corner instead of averaged would be off by ~k h / 2 ≈ 1e-2.
  // A linear element cannot represent the quadratic field: its interpolant's gradient is
  // off by O(k h) (a discretization error, not a property of the rotation choice), so it
  // only gets the looser bound k h.
  std::mt19937 rng(53);
  const double twist = 0.005;
  for (int n = 1; n <= 3; ++n) {
    Element e = makeElement(rng, n);
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) centroid += 0.25 * Eigen::Map<const Eigen::Vector3d>(e.corners + 3 * i);
    const Eigen::Vector3d shift = Eigen::Vector3d(0, 0, 10) - centroid;  // K, ∇λ unchanged
    double h = 0.0;
    for (int k = 0; k < e.nodes; ++k) {
      e.rest.segment<3>(3 * k) += shift;
      h = std::max(h, (e.rest.segment<3>(3 * k) - Eigen::Vector3d(0, 0, 10)).norm());
    }
    const Eigen::Matrix3d q = randomRotation(rng);
    const Eigen::Matrix3d expected =
        q * Eigen::AngleAxisd(twist * 10.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const VectorXd x = interpolate(e, [&](const Eigen::Vector3d& X) {
      const double delta = X.z() - 10.0;
      return Eigen::Vector3d(expected * (X + twist * delta * Eigen::Vector3d::UnitZ().cross(X)));
    });
    const Eigen::AngleAxisd diff(rotationOf(e, x).transpose() * expected);
    EXPECT_LT(std::fabs(diff.angle()), n == 1 ? twist * 2 * h : 1e-3) << "n=" << n;
  }
}

// ---- corotated force and stiffness -------------------------------------------------------

TEST(DeformCorotatedElement, RigidMotionGivesZeroForceEveryDegree) {
  std::mt19937 rng(54);
  for (int n = 1; n <= 3; ++n)
    for (int trial = 0; trial < 10; ++trial) {
      const Element e = makeElement(rng, n);
      // Large rotations, including one near 180°, and a large translation.
      Eigen::Matrix3d q = randomRotation(rng);
      if (trial == 0)
        q = Eigen::AngleAxisd(3.14159, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
      const VectorXd x = affine(e, q, Eigen::Vector3d(30, -20, 10));
      const VectorXd f = force(e, x, rotationOf(e, x));
      // Scale of an elastic force for unit displacement: ‖K‖·|x|. R equals Q to ~1e-15, so
      // the residual is round-off of K times positions ~40: 1e-12 relative.
      const double scale = e.k.cwiseAbs().maxCoeff() * x.cwiseAbs().maxCoeff();
      EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-12 * scale) << "n=" << n << " trial " << trial;
    }
}

TEST(DeformCorotatedElement, SmallDeformationGivesTheLinearForceInTheRotatedFrame) {
  std::mt19937 rng(55);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 1; n <= 3; ++n) {
    const Element e = makeElement(rng, n);
    VectorXd disp(e.rest.size());
    for (int i = 0; i < disp.size(); ++i) disp[i] = u(rng);
    const double eps = 1e-6;
    const VectorXd linear = -e.k * (eps * disp);
    // Unrotated: x = x0 + εu. Rotated and moved: x = Q(x0 + εu) + t must give Q·f.
    const Eigen::Matrix3d q = randomRotation(rng);
    const Eigen::Vector3d t(1, 2, 3);
    const VectorXd x1 = e.rest + eps * disp;
    VectorXd x2(x1.size()), expected2(x1.size());
    for (int k = 0; k < e.nodes; ++k) {
      x2.segment<3>(3 * k) = q * x1.segment<3>(3 * k) + t;
      expected2.segment<3>(3 * k) = q * linear.segment<3>(3 * k);
    }
    // The corotation changes the force only at O(ε²) (an infinitesimal rotation of the
    // rest shape is a null vector of K), so the relative difference is O(ε) = 1e-6;
    // 1e-4 leaves room for cond(K) amplification, and a wrong R would give O(1).
    const VectorXd f1 = force(e, x1, rotationOf(e, x1));
    const VectorXd f2 = force(e, x2, rotationOf(e, x2));
    EXPECT_LT((f1 - linear).norm(), 1e-4 * linear.norm()) << "n=" << n;
    EXPECT_LT((f2 - expected2).norm(), 1e-4 * linear.norm()) << "n=" << n;
  }
}

TEST(DeformCorotatedElement, RotatedStiffnessIsBlockRotationOfK) {
  std::mt19937 rng(56);
  for (int n = 1; n <= 3; ++n) {
    const Element e = makeElement(rng, n);
    const Mat3R r = randomRotation(rng);
    const int d = 3 * e.nodes;
    std::vector<double> out(d * d);
    corotatedStiffness(e.nodes, e.stiffness.data(), r.data(), out.data());
    const MatrixXd got =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            out.data(), d, d);
    MatrixXd big = MatrixXd::Zero(d, d);
    for (int k = 0; k < e.nodes; ++k) big.block<3, 3>(3 * k, 3 * k) = r;
    const MatrixXd expected = big * e.k * big.transpose();
    const double scale = e.k.cwiseAbs().maxCoeff();
    EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-13 * scale) << "n=" << n;
    EXPECT_LT((got - got.transpose()).cwiseAbs().maxCoeff(), 1e-13 * scale) << "n=" << n;
    // It is the Jacobian of the force for fixed R: f(x + δ) − f(x) = −K_rot δ exactly.
    VectorXd x = e.rest, delta(d);
    for (int i = 0; i < d; ++i) delta[i] = std::sin(1.0 + i);
    const VectorXd df = force(e, x + delta, r) - force(e, x, r);
    EXPECT_LT((df + got * delta).norm(), 1e-11 * scale * delta.norm()) << "n=" << n;
  }
}

TEST(DeformCorotatedElement, CollapsedElementGivesFiniteRestoringForce) {
  std::mt19937 rng(57);
  for (int n = 1; n <= 3; ++n) {
    const Element e = makeElement(rng, n);
    VectorXd x = VectorXd::Zero(e.rest.size());  // every node at the origin: F = 0
    const Eigen::Matrix3d r = rotationOf(e, x);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
    const VectorXd f = force(e, x, r);
    EXPECT_TRUE(f.allFinite());
    // The force does work towards the rotated rest shape: f·(R x0 − x) = dᵀ K d > 0.
    VectorXd target(x.size());
    for (int k = 0; k < e.nodes; ++k) target.segment<3>(3 * k) = r * e.rest.segment<3>(3 * k);
    EXPECT_GT(f.dot(target - x), 0.0) << "n=" << n;
  }
}

// The linear-tet kernel body (gpu_kernels/linear_tet_kernels.h) against the generic path at
// degree 1: the same F bit for bit, the force of the generic −R K (Rᵀx − x0) and the blocks of
// R K Rᵀ. The rotations differ only by the iteration's stopping tolerance
// (kCorotationTolerance), so the force agrees to that relative to the stress it rotates.
TEST(DeformCorotatedElement, LinearTetKernelEqualsTheGenericPath) {
  std::mt19937 rng(58);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  const double lambda = 2.0e5, mu = 8.0e4;
  for (int trial = 0; trial < 50; ++trial) {
    const Element e = makeElement(rng, 1);
    const Eigen::Matrix3d q = randomRotation(rng);
    VectorXd x = affine(e, q, Eigen::Vector3d(1, 2, 3));
    for (int i = 0; i < x.size(); ++i) x[i] += u(rng) * std::cbrt(e.volume);
    Mat3R generic;
    bbAverageDeformationGradient(1, x.data(), e.baryGrad, generic.data());
    Mat3R f;
    kernels::linearTetDeformationGradient(x.data(), e.baryGrad, f.data());
    EXPECT_EQ(std::memcmp(f.data(), generic.data(), sizeof(double) * 9), 0);

    // Warm-started as a step is: from the element's rigid part.
    const Eigen::Quaterniond start(q);
    double quat[4] = {start.w(), start.x(), start.y(), start.z()}, got[12], rotatedGrad[12];
    kernels::corotateLinearTet(x.data(), e.baryGrad, e.volume, lambda, mu, quat, got, rotatedGrad);
    const Eigen::Matrix3d r = rotationOf(e, x);
    const VectorXd expected = force(e, x, r);
    const double stress = e.k.cwiseAbs().maxCoeff() * (x - e.rest).cwiseAbs().maxCoeff();
    EXPECT_LT((Eigen::Map<const VectorXd>(got, 12) - expected).cwiseAbs().maxCoeff(),
              10 * kernels::kCorotationTolerance * stress)
        << "trial " << trial;

    // Blocks with the kernel's own rotation, so they are compared to round-off.
    Mat3R own;
    kernels::rotationFromQuaternion(quat, own.data());
    std::vector<double> rotated(144);
    corotatedStiffness(4, e.stiffness.data(), own.data(), rotated.data());
    const double scale = e.k.cwiseAbs().maxCoeff();
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        double block[9] = {};
        kernels::addLinearTetBlock(rotatedGrad, e.baryGrad, a, b, e.volume, lambda, mu, 1.0, block);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            EXPECT_NEAR(block[3 * i + j], rotated[12 * (3 * a + i) + 3 * b + j], 1e-12 * scale);
      }
  }
}

}  // namespace
}  // namespace vp

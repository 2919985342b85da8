// BB element mass and stiffness: invariants, and an independent check of the analytic
// formulas of REFERENCES.md against Gauss quadrature of the textbook integrals.
#include "deform/bb_element_matrices.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "deform/bb_multi_index.h"
#include "deform_test_util.h"

namespace vp {
namespace {

using deform_test::randomTet;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kDensity = 1070.0;
constexpr double kLambda = 2.9e5;  // with kMu: E ≈ 1.4e5 Pa, ν ≈ 0.43 (soft, nearly incompressible)
constexpr double kMu = 5.0e4;

MatrixXd mass(int n, const double* corners) {
  const int N = bbNodeCount(n);
  MatrixXd m(N, N);
  std::vector<double> buffer(N * N);
  EXPECT_EQ(bbMassMatrix(n, corners, kDensity, buffer.data()), Status::Ok) << lastError();
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) m(i, j) = buffer[i * N + j];
  return m;
}

MatrixXd stiffness(int n, const double* corners, double lambda = kLambda, double mu = kMu) {
  const int D = 3 * bbNodeCount(n);
  std::vector<double> buffer(D * D);
  EXPECT_EQ(bbStiffnessMatrix(n, corners, lambda, mu, buffer.data()), Status::Ok) << lastError();
  MatrixXd k(D, D);
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) k(i, j) = buffer[i * D + j];
  return k;
}

double volumeOf(const double* c) {
  Eigen::Matrix3d dm;
  for (int k = 1; k < 4; ++k)
    for (int a = 0; a < 3; ++a) dm(a, k - 1) = c[3 * k + a] - c[a];
  return dm.determinant() / 6.0;
}

VectorXd restNodes(int n, const double* corners) {
  VectorXd x(3 * bbNodeCount(n));
  EXPECT_EQ(bbRestNodePositions(n, corners, x.data()), Status::Ok);
  return x;
}

// ---- independent quadrature --------------------------------------------------------------

// Gauss–Legendre nodes/weights on [0,1] by Newton on P_m (no table to mistype).
void gaussLegendre(int m, std::vector<double>& x, std::vector<double>& w) {
  x.resize(m);
  w.resize(m);
  const double pi = std::acos(-1.0);
  for (int i = 0; i < m; ++i) {
    double t = std::cos(pi * (i + 0.75) / (m + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = t;
      for (int k = 2; k <= m; ++k) {
        const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = m * (t * p1 - p0) / (t * t - 1.0);
      const double step = p1 / dp;
      t -= step;
      if (std::fabs(step) < 1e-16) break;
    }
    x[i] = 0.5 * (1.0 - t);
    w[i] = 1.0 / ((1.0 - t * t) * dp * dp);  // 2/((1−t²)P'²) halved for [0,1]
  }
}

struct QuadPoint {
  double bary[4];
  double weight;  // includes the physical volume: Σ weight = V
};

// Collapsed (Duffy) tensor Gauss rule: ξ = u, η = v(1−u), ζ = w(1−u)(1−v), Jacobian
// (1−u)²(1−v). 6 points per direction integrate degree 11 in each of u, v, w; the
// integrands here have degree ≤ 2n + 2 ≤ 8 in u (the B·B product of the cubic mass, plus
// the Jacobian), so the rule is exact up to round-off.
std::vector<QuadPoint> tetQuadrature(double volume) {
  std::vector<double> x, w;
  gaussLegendre(6, x, w);
  std::vector<QuadPoint> points;
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = 0; j < x.size(); ++j)
      for (size_t k = 0; k < x.size(); ++k) {
        const double u = x[i], v = x[j], s = x[k];
        const double xi = u, eta = v * (1 - u), zeta = s * (1 - u) * (1 - v);
        QuadPoint q;
        q.bary[0] = 1 - xi - eta - zeta;
        q.bary[1] = xi;
        q.bary[2] = eta;
        q.bary[3] = zeta;
        // Reference tet volume is 1/6, so the physical weight is 6V · (ref weight).
        q.weight = 6.0 * volume * w[i] * w[j] * w[k] * (1 - u) * (1 - u) * (1 - v);
        points.push_back(q);
      }
  return points;
}

// B_α and ∂B_α/∂λ_c straight from the power form (product rule), deliberately not via the
// degree-reduction identity the analytic formula uses.
double basisPowerForm(const BBMultiIndex& a, const double* l) {
  double v = bbMultinomial(a);
  for (int i = 0; i < 4; ++i) v *= std::pow(l[i], a.a[i]);
  return v;
}
double basisDerivativePowerForm(const BBMultiIndex& a, const double* l, int c) {
  if (a.a[c] == 0) return 0.0;
  double v = bbMultinomial(a) * a.a[c] * std::pow(l[c], a.a[c] - 1);
  for (int i = 0; i < 4; ++i)
    if (i != c) v *= std::pow(l[i], a.a[i]);
  return v;
}

// Barycentric gradients recomputed here from the inverse of [X; 1] (another route than
// the Dm⁻¹ rows of the implementation): λ = A⁻¹ [X; 1], so ∇λ_c = columns 0..2 of row c.
Eigen::Matrix<double, 4, 3> baryGradients(const double* c) {
  Eigen::Matrix4d a;
  for (int i = 0; i < 4; ++i) {
    for (int r = 0; r < 3; ++r) a(r, i) = c[3 * i + r];
    a(3, i) = 1.0;
  }
  const Eigen::Matrix4d inv = a.inverse();
  return inv.leftCols<3>();
}

MatrixXd quadratureStiffness(int n, const double* corners, double lambda, double mu) {
  const int N = bbNodeCount(n);
  const BBMultiIndex* nodes = bbMultiIndices(n);
  const auto g = baryGradients(corners);
  // Voigt order xx, yy, zz, yz, xz, xy with engineering shear strains.
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) d(i, i) += 2 * mu;
  for (int i = 3; i < 6; ++i) d(i, i) = mu;
  MatrixXd k = MatrixXd::Zero(3 * N, 3 * N);
  for (const QuadPoint& q : tetQuadrature(volumeOf(corners))) {
    MatrixXd b = MatrixXd::Zero(6, 3 * N);
    for (int a = 0; a < N; ++a) {
      Eigen::Vector3d grad = Eigen::Vector3d::Zero();
      for (int c = 0; c < 4; ++c)
        grad += basisDerivativePowerForm(nodes[a], q.bary, c) * g.row(c).transpose();
      b(0, 3 * a) = grad.x();
      b(1, 3 * a + 1) = grad.y();
      b(2, 3 * a + 2) = grad.z();
      b(3, 3 * a + 1) = grad.z();
      b(3, 3 * a + 2) = grad.y();
      b(4, 3 * a) = grad.z();
      b(4, 3 * a + 2) = grad.x();
      b(5, 3 * a) = grad.y();
      b(5, 3 * a + 1) = grad.x();
    }
    k += q.weight * b.transpose() * d * b;
  }
  return k;
}

MatrixXd quadratureMass(int n, const double* corners, double density) {
  const int N = bbNodeCount(n);
  const BBMultiIndex* nodes = bbMultiIndices(n);
  MatrixXd m = MatrixXd::Zero(N, N);
  for (const QuadPoint& q : tetQuadrature(volumeOf(corners)))
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j)
        m(i, j) += q.weight * density * basisPowerForm(nodes[i], q.bary) *
                   basisPowerForm(nodes[j], q.bary);
  return m;
}

// ---- mass --------------------------------------------------------------------------------

TEST(DeformElementMatrices, MassSumsToDensityTimesVolumeAndIsSpd) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    double c[12];
    randomTet(rng, c);
    const double rhoV = kDensity * volumeOf(c);
    for (int n = 1; n <= 3; ++n) {
      const MatrixXd m = mass(n, c);
      // Partition of unity: Σ_αβ ∫ρ B_α B_β = ρV. Sums of ≤ 400 positive terms: 1e-13 rel.
      EXPECT_NEAR(m.sum(), rhoV, 1e-13 * rhoV) << "n=" << n;
      EXPECT_EQ((m - m.transpose()).cwiseAbs().maxCoeff(), 0.0);
      const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(m);
      // The BB mass is well conditioned (cond ≈ 10..300 for n ≤ 3); its smallest eigenvalue
      // is far above round-off, so "> 1e-6 of the largest" is a real positivity check.
      EXPECT_GT(eig.eigenvalues().minCoeff(), 1e-6 * eig.eigenvalues().maxCoeff()) << "n=" << n;
    }
  }
}

TEST(DeformElementMatrices, LumpedMassIsPositiveAndUniform) {
  std::mt19937 rng(12);
  double c[12];
  randomTet(rng, c);
  for (int n = 1; n <= 3; ++n) {
    double lumped[kBBMaxNodes];
    ASSERT_EQ(bbLumpedMass(n, c, kDensity, lumped), Status::Ok);
    const double expected = kDensity * volumeOf(c) / bbBinomial(n + 3, 3);
    const MatrixXd m = mass(n, c);
    for (int i = 0; i < bbNodeCount(n); ++i) {
      EXPECT_GT(lumped[i], 0.0);
      EXPECT_NEAR(lumped[i], expected, 1e-13 * expected);
      EXPECT_NEAR(lumped[i], m.row(i).sum(), 1e-13 * expected);
    }
  }
}

TEST(DeformElementMatrices, MassMatchesQuadrature) {
  std::mt19937 rng(13);
  double c[12];
  randomTet(rng, c);
  for (int n = 1; n <= 3; ++n) {
    const MatrixXd analytic = mass(n, c);
    const MatrixXd numeric = quadratureMass(n, c, kDensity);
    // Exact rule; 216 quadrature terms of round-off each: 1e-12 of the largest entry.
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-12 * analytic.cwiseAbs().maxCoeff())
        << "n=" << n;
  }
}

// ---- stiffness ---------------------------------------------------------------------------

TEST(DeformElementMatrices, StiffnessMatchesQuadratureOfBtDB) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 3; ++trial) {
    double c[12];
    randomTet(rng, c);
    for (int n = 1; n <= 3; ++n) {
      const MatrixXd analytic = stiffness(n, c);
      const MatrixXd numeric = quadratureStiffness(n, c, kLambda, kMu);
      const double scale = analytic.cwiseAbs().maxCoeff();
      EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-11 * scale) << "n=" << n;
    }
  }
}

TEST(DeformElementMatrices, StiffnessSymmetricPsdWithExactlySixRigidModes) {
  std::mt19937 rng(22);
  for (int trial = 0; trial < 5; ++trial) {
    double c[12];
    randomTet(rng, c);
    for (int n = 1; n <= 3; ++n) {
      const MatrixXd k = stiffness(n, c);
      const double scale = k.cwiseAbs().maxCoeff();
      // The formula is symmetric term by term up to the order of additions.
      EXPECT_LT((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-14 * scale);
      const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(k);
      const VectorXd ev = eig.eigenvalues();  // ascending
      const double top = ev.maxCoeff();
      // Rigid-mode eigenvalues are round-off, ~1e-15 of the top; the 7th (softest
      // deformation) of these tets is above 1e-4 of it, so 1e-10 separates them cleanly.
      for (int i = 0; i < 6; ++i) EXPECT_LT(std::fabs(ev[i]), 1e-10 * top) << "n=" << n;
      EXPECT_GT(ev[6], 1e-6 * top) << "n=" << n << ": more than 6 zero modes";
      EXPECT_GT(ev.minCoeff(), -1e-10 * top) << "n=" << n;
    }
  }
}

TEST(DeformElementMatrices, TranslationsAndInfinitesimalRotationsCarryNoForce) {
  std::mt19937 rng(23);
  double c[12];
  randomTet(rng, c);
  for (int n = 1; n <= 3; ++n) {
    const MatrixXd k = stiffness(n, c);
    const VectorXd x = restNodes(n, c);
    const int N = bbNodeCount(n);
    const double kNorm = k.cwiseAbs().maxCoeff() * 3 * N;  // bound on ‖K‖∞
    for (int axis = 0; axis < 3; ++axis) {
      VectorXd t = VectorXd::Zero(3 * N), r(3 * N);
      Eigen::Vector3d w = Eigen::Vector3d::Zero();
      w[axis] = 1.0;
      for (int i = 0; i < N; ++i) {
        t[3 * i + axis] = 1.0;
        r.segment<3>(3 * i) = w.cross(Eigen::Vector3d(x.segment<3>(3 * i)));
      }
      // Round-off of a product with entries of size ‖K‖·‖u‖: 1e-13 relative.
      EXPECT_LT((k * t).cwiseAbs().maxCoeff(), 1e-13 * kNorm) << "n=" << n << " axis " << axis;
      EXPECT_LT((k * r).cwiseAbs().maxCoeff(), 1e-13 * kNorm * r.cwiseAbs().maxCoeff())
          << "n=" << n << " axis " << axis;
    }
  }
}

TEST(DeformElementMatrices, PatchTestAffineFieldGivesConstantStrainEnergy) {
  std::mt19937 rng(24);
  for (int trial = 0; trial < 5; ++trial) {
    double c[12];
    randomTet(rng, c);
    const Eigen::Matrix3d g = deform_test::randomMatrix(rng, -0.1, 0.1);  // ∇u
    const Eigen::Matrix3d eps = 0.5 * (g + g.transpose());
    const double tr = eps.trace();
    const double expected =
        0.5 * volumeOf(c) * (kLambda * tr * tr + 2.0 * kMu * (eps.array() * eps.array()).sum());
    for (int n = 1; n <= 3; ++n) {
      const MatrixXd k = stiffness(n, c);
      const VectorXd x = restNodes(n, c);
      VectorXd u(x.size());
      // x = F X with F = I + ∇u; the displacement u = ∇u X at every control point.
      for (int i = 0; i < x.size() / 3; ++i)
        u.segment<3>(3 * i) = g * Eigen::Vector3d(x.segment<3>(3 * i));
      const double energy = 0.5 * u.dot(k * u);
      // Energy is a cancellation-free quadratic form here except for the translation part
      // of u (nodes are far from the origin): 1e-10 relative covers that loss of digits.
      EXPECT_NEAR(energy, expected, 1e-10 * expected) << "n=" << n;
    }
  }
}

// ---- bad input ---------------------------------------------------------------------------

TEST(DeformElementMatrices, RejectsBadInputWithNamedField) {
  const double good[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double inverted[12] = {0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1};
  const double flat[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  double nanTet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  nanTet[7] = std::nan("");
  std::vector<double> out(60 * 60);
  auto expectError = [](Status s, const char* fragment) {
    EXPECT_EQ(s, Status::InvalidArgument);
    EXPECT_NE(std::string(lastError()).find(fragment), std::string::npos) << lastError();
  };
  expectError(bbMassMatrix(4, good, 1.0, out.data()), "degree = 4");
  expectError(bbMassMatrix(1, good, -2.0, out.data()), "density = -2");
  expectError(bbStiffnessMatrix(2, good, 1.0, 0.0, out.data()), "mu = 0");
  expectError(bbStiffnessMatrix(2, good, -1.0, 1.0, out.data()), "lambda = -1");
  expectError(bbStiffnessMatrix(3, inverted, 1.0, 1.0, out.data()), "inverted");
  expectError(bbStiffnessMatrix(3, flat, 1.0, 1.0, out.data()), "degenerate");
  expectError(bbLumpedMass(2, nanTet, 1.0, out.data()), "restCorners[2][1]");
  EXPECT_EQ(bbStiffnessMatrix(1, good, 1.0, 1.0, out.data()), Status::Ok);
}

}  // namespace
}  // namespace vp

#include "deform/bb_element_matrices.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "deform/bb_multi_index.h"

namespace vp {
namespace {

Status checkDegree(const char* where, int degree) {
  if (degree < 1 || degree > kBBMaxDegree)
    return fail(Status::InvalidArgument, "%s: degree = %d, expected 1, 2 or 3", where, degree);
  return Status::Ok;
}

}  // namespace

Status bbBarycentricGradients(const double restCorners[12], double baryGrad[12],
                              double* volume) {
  for (int i = 0; i < 12; ++i)
    if (!std::isfinite(restCorners[i]))
      return fail(Status::InvalidArgument, "restCorners[%d][%d] = %g is not finite", i / 3,
                  i % 3, restCorners[i]);
  // Dm has the edge vectors X_k − X_0 (k = 1..3) as columns; λ_k = row k−1 of Dm⁻¹ applied
  // to X − X_0, so ∇λ_k is that row and ∇λ_0 = −Σ ∇λ_k (the λ sum to one).
  Eigen::Matrix3d dm;
  for (int k = 1; k < 4; ++k)
    for (int a = 0; a < 3; ++a) dm(a, k - 1) = restCorners[3 * k + a] - restCorners[a];
  double longest = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double d = restCorners[3 * j + a] - restCorners[3 * i + a];
        d2 += d * d;
      }
      longest = std::max(longest, std::sqrt(d2));
    }
  const double signedVolume = dm.determinant() / 6.0;
  // A regular tet has V ≈ 0.118 L³; 1e-10 L³ only rejects tets that are flat to round-off
  // or so thin that Dm⁻¹ would carry more error than signal.
  const double minVolume = 1e-10 * longest * longest * longest;
  if (signedVolume < 0.0 && -signedVolume >= minVolume)
    return fail(Status::InvalidArgument,
                "restCorners describe an inverted tet (signed volume %g); swap two vertices",
                signedVolume);
  if (!(signedVolume >= minVolume))
    return fail(Status::InvalidArgument,
                "restCorners describe a degenerate tet (volume %g, longest edge %g)",
                signedVolume, longest);
  const Eigen::Matrix3d inv = dm.inverse();
  for (int a = 0; a < 3; ++a) {
    baryGrad[a] = -(inv(0, a) + inv(1, a) + inv(2, a));
    for (int k = 1; k < 4; ++k) baryGrad[3 * k + a] = inv(k - 1, a);
  }
  *volume = signedVolume;
  return Status::Ok;
}

Status bbMassMatrix(int degree, const double restCorners[12], double density, double* mass) {
  VP_TRY(checkDegree("bbMassMatrix", degree));
  if (!(std::isfinite(density) && density > 0.0))
    return fail(Status::InvalidArgument, "bbMassMatrix: density = %g, expected > 0", density);
  double grad[12];
  double volume = 0.0;
  if (Status s = bbBarycentricGradients(restCorners, grad, &volume); s != Status::Ok)
    return addErrorContext(s, "bbMassMatrix");
  const int n = bbNodeCount(degree);
  const BBMultiIndex* nodes = bbMultiIndices(degree);
  const double scale = density * volume / bbBinomial(2 * degree + 3, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) mass[i * n + j] = scale * bbGramFactor(nodes[i], nodes[j]);
  return Status::Ok;
}

Status bbLumpedMass(int degree, const double restCorners[12], double density,
                    double* lumpedMass) {
  VP_TRY(checkDegree("bbLumpedMass", degree));
  double full[kBBMaxNodes * kBBMaxNodes];
  if (Status s = bbMassMatrix(degree, restCorners, density, full); s != Status::Ok)
    return addErrorContext(s, "bbLumpedMass");
  const int n = bbNodeCount(degree);
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) sum += full[i * n + j];
    lumpedMass[i] = sum;
  }
  return Status::Ok;
}

Status bbStiffnessMatrix(int degree, const double restCorners[12], double lambda, double mu,
                         double* stiffness) {
  VP_TRY(checkDegree("bbStiffnessMatrix", degree));
  if (!(std::isfinite(mu) && mu > 0.0))
    return fail(Status::InvalidArgument, "bbStiffnessMatrix: mu = %g, expected > 0", mu);
  if (!(std::isfinite(lambda) && 3.0 * lambda + 2.0 * mu > 0.0))
    return fail(Status::InvalidArgument,
                "bbStiffnessMatrix: lambda = %g, expected finite and > -2/3 mu = %g", lambda,
                -2.0 / 3.0 * mu);
  double g[12];
  double volume = 0.0;
  if (Status s = bbBarycentricGradients(restCorners, g, &volume); s != Status::Ok)
    return addErrorContext(s, "bbStiffnessMatrix");

  const int n = degree;
  const int count = bbNodeCount(n);
  const int dim = 3 * count;
  const BBMultiIndex* nodes = bbMultiIndices(n);
  // ∂B^n_α = n Σ_c B^{n−1}_{α−e_c} ∇λ_c and ∫ B^{n−1}_γ B^{n−1}_δ = V G_{n−1}/C(2n+1, 3), so
  // the product of two gradients integrates to n² V G_{n−1} / C(2n+1, 3) = 3nV/(4n²−1) · G.
  const double scale = 3.0 * n * volume / (4.0 * n * n - 1.0);
  std::fill(stiffness, stiffness + dim * dim, 0.0);
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < count; ++j) {
      double block[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      for (int c = 0; c < 4; ++c) {
        if (nodes[i].a[c] == 0) continue;
        BBMultiIndex ai = nodes[i];
        --ai.a[c];
        const double* gc = g + 3 * c;
        for (int d = 0; d < 4; ++d) {
          if (nodes[j].a[d] == 0) continue;
          BBMultiIndex bj = nodes[j];
          --bj.a[d];
          const double* gd = g + 3 * d;
          const double w = scale * bbGramFactor(ai, bj);
          const double dot = gc[0] * gd[0] + gc[1] * gd[1] + gc[2] * gd[2];
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
              block[3 * a + b] += w * (lambda * gc[a] * gd[b] + mu * gc[b] * gd[a] +
                                       (a == b ? mu * dot : 0.0));
        }
      }
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          stiffness[(3 * i + a) * dim + 3 * j + b] = block[3 * a + b];
    }
  }
  return Status::Ok;
}

Status bbRestNodePositions(int degree, const double restCorners[12], double* nodePositions) {
  VP_TRY(checkDegree("bbRestNodePositions", degree));
  const BBMultiIndex* nodes = bbMultiIndices(degree);
  for (int k = 0; k < bbNodeCount(degree); ++k)
    for (int a = 0; a < 3; ++a) {
      double x = 0.0;
      for (int i = 0; i < 4; ++i) x += nodes[k].a[i] * restCorners[3 * i + a];
      nodePositions[3 * k + a] = x / degree;
    }
  return Status::Ok;
}

}  // namespace vp

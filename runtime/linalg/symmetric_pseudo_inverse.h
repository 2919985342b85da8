// Inverse of a small symmetric positive semi-definite block (the diagonal blocks the
// multigrid smoothers invert). Directions with (numerically) zero stiffness are
// constraint-filtered or inert and must get zero correction, not a huge one: Cholesky when
// the block is safely definite (the common case, cheap), otherwise an eigen-decomposition
// pseudo-inverse.
#pragma once

#include <algorithm>

#include <Eigen/Dense>

namespace vp {

template <int N>
Eigen::Matrix<double, N, N, Eigen::RowMajor> symmetricPseudoInverse(const Eigen::Matrix<double, N, N, Eigen::RowMajor>& m) {
  Eigen::LLT<Eigen::Matrix<double, N, N>> llt(m);
  if (llt.info() == Eigen::Success) {
    const auto& L = llt.matrixL();
    double lo = L(0, 0), hi = L(0, 0);
    for (int k = 1; k < N; ++k) lo = std::min(lo, L(k, k)), hi = std::max(hi, L(k, k));
    // Pivots squared bound the eigenvalues' spread well enough to spot near-singular blocks.
    if (lo * lo > 1e-9 * hi * hi) return llt.solve(Eigen::Matrix<double, N, N>::Identity());
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(m);
  const auto& values = eig.eigenvalues();
  const double cutoff = 1e-10 * std::max(values.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::Matrix<double, N, 1> inv;
  for (int k = 0; k < N; ++k) inv[k] = values[k] > cutoff ? 1.0 / values[k] : 0.0;
  return eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace vp

#include "deform/linear_tet_corotation.h"

#include "deform/deformation_gradient.h"
#include "deform/polar_decomposition.h"

namespace vp {

void corotateLinearTet(const double x[12], const double grad[12], double volume, double lambda, double mu,
                       double quat[4], double force[12], double rotatedGrad[12]) {
  double F[9], R[9];
  bbAverageDeformationGradient(1, x, grad, F);
  // Warm-started from last step's rotation this converges in 2-3 iterations (inverted F
  // falls back to the SVD inside).
  if (polarRotationIterative(F, quat, R, 20, 1e-6) < 0) {
    for (int i = 0; i < 9; ++i) R[i] = (i % 4 == 0) ? 1.0 : 0.0;  // non-finite F: the divergence guard reports it
  }
  // Unrotated deformation S = Rᵀ F, strain ε = sym(S) − I, stress σ = λ tr(ε) I + 2μ ε.
  double S[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) S[3 * i + j] = R[i] * F[j] + R[3 + i] * F[3 + j] + R[6 + i] * F[6 + j];
  double eps[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) eps[3 * i + j] = 0.5 * (S[3 * i + j] + S[3 * j + i]) - (i == j ? 1.0 : 0.0);
  const double trace = eps[0] + eps[4] + eps[8];
  double sigma[9];
  for (int i = 0; i < 9; ++i) sigma[i] = 2.0 * mu * eps[i] + (i % 4 == 0 ? lambda * trace : 0.0);
  // Rotated gradients h_a = R g_a, and forces f_a = −V R σ g_a.
  double* h = rotatedGrad;
  for (int a = 0; a < 4; ++a) {
    const double* g = grad + 3 * a;
    double sg[3];
    for (int i = 0; i < 3; ++i) {
      h[3 * a + i] = R[3 * i] * g[0] + R[3 * i + 1] * g[1] + R[3 * i + 2] * g[2];
      sg[i] = sigma[3 * i] * g[0] + sigma[3 * i + 1] * g[1] + sigma[3 * i + 2] * g[2];
    }
    for (int i = 0; i < 3; ++i)
      force[3 * a + i] = -volume * (R[3 * i] * sg[0] + R[3 * i + 1] * sg[1] + R[3 * i + 2] * sg[2]);
  }
}

}  // namespace vp

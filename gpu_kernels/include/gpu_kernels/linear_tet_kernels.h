// The per-element kernel bodies of corotational linear tetrahedra (degree 1), specialised
// because they are the hot loops of every linear deformable step; a CPU loop and a CUDA thread
// run them alike.
//
// For a linear tet the rest stiffness is K_ab = V [λ g_a g_bᵀ + μ g_b g_aᵀ + μ (g_a·g_b) I]
// (g the rest barycentric gradients), so the rotated stiffness R K_ab Rᵀ is the same
// expression with rotated gradients h = R g (R I Rᵀ = I): no 12x12 matrix is stored or
// multiplied, and a block costs a few dozen flops. The force −R K (Rᵀx − x0) is −V R σ g_a
// with the small strain of the unrotated deformation, ε = sym(Rᵀ F) − I and
// σ = λ tr(ε) I + 2μ ε. Both equal the generic BB path (runtime/deform/corotated_element.h)
// at degree 1; a unit test checks it.
//
// Arrays: x 4x3 corner positions, grad 4x3 rest gradients, quat (w,x,y,z) the rotation warm
// start (in) and result (out), force 4x3 and rotatedGrad 4x3 (written).
#pragma once

#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/polar_kernels.h"

namespace vp::kernels {

// F = Σ_a x_a g_aᵀ, the deformation gradient of a linear tet (runtime/deform/
// deformation_gradient.h at degree 1, same order of sums).
VP_HOST_DEVICE inline void linearTetDeformationGradient(const double x[12], const double grad[12], double F[9]) {
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int c = 0; c < 4; ++c) s += x[3 * c + a] * grad[3 * c + j];
      F[3 * a + j] = s;
    }
}

VP_HOST_DEVICE inline void corotateLinearTet(const double x[12], const double grad[12], double volume, double lambda,
                                             double mu, double quat[4], double force[12], double rotatedGrad[12]) {
  double F[9], R[9];
  linearTetDeformationGradient(x, grad, F);
  // A non-finite F leaves R the warm start's rotation; the identity is as good, and the
  // divergence guard reports the body anyway.
  if (polarRotationIterative(F, quat, R, kCorotationIterations, kCorotationTolerance) < 0)
    for (int i = 0; i < 9; ++i) R[i] = (i % 4 == 0) ? 1.0 : 0.0;
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

// out (3x3 row-major) += scale * R K_ab Rᵀ of the element, from its rotated gradients.
VP_HOST_DEVICE inline void addLinearTetBlock(const double* rotatedGrad, const double* grad, int a, int b, double volume,
                                             double lambda, double mu, double scale, double* out) {
  const double* ha = rotatedGrad + 3 * a;
  const double* hb = rotatedGrad + 3 * b;
  const double* ga = grad + 3 * a;
  const double* gb = grad + 3 * b;
  const double s = scale * volume;
  const double shear = mu * (ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out[3 * i + j] += s * (lambda * ha[i] * hb[j] + mu * hb[i] * ha[j] + (i == j ? shear : 0.0));
}

}  // namespace vp::kernels

// The per-element kernels of corotational linear tetrahedra (degree 1), specialised because
// they are the hot loops of every linear deformable step.
//
// For a linear tet the rest stiffness is K_ab = V [λ g_a g_bᵀ + μ g_b g_aᵀ + μ (g_a·g_b) I]
// (g the rest barycentric gradients), so the rotated stiffness R K_ab Rᵀ is the same
// expression with rotated gradients h = R g (R I Rᵀ = I): no 12x12 matrix is stored or
// multiplied, and a block costs a few dozen flops. The force −R K (Rᵀx − x0) is −V R σ g_a
// with the small strain of the unrotated deformation, ε = sym(Rᵀ F) − I and
// σ = λ tr(ε) I + 2μ ε. Both equal the generic BB path (corotated_element.h) at degree 1; a
// unit test checks it.
//
// Arrays: x 4x3 corner positions, grad 4x3 rest gradients, quat (w,x,y,z) the rotation warm
// start (in) and result (out), force 4x3 and rotatedGrad 4x3 (written). Pure, no allocation.
#pragma once

namespace vp {

void corotateLinearTet(const double x[12], const double grad[12], double volume, double lambda, double mu,
                       double quat[4], double force[12], double rotatedGrad[12]);

// out (3x3 row-major) += scale * R K_ab Rᵀ of the element, from its rotated gradients.
inline void addLinearTetBlock(const double* rotatedGrad, const double* grad, int a, int b, double volume,
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

}  // namespace vp

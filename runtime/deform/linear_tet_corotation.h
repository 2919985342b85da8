// The per-element kernel of corotational linear tetrahedra (degree 1), specialised because
// it is the hot loop of every linear deformable step.
//
// For a linear tet the rest stiffness is K_ab = V [λ g_a g_bᵀ + μ g_b g_aᵀ + μ (g_a·g_b) I]
// (g the rest barycentric gradients), so the rotated stiffness R K_ab Rᵀ is the same
// expression with rotated gradients h = R g (R I Rᵀ = I): no 12x12 matrix is stored or
// multiplied. The force −R K (Rᵀx − x0) is −V R σ g_a with the small strain of the
// unrotated deformation, ε = sym(Rᵀ F) − I and σ = λ tr(ε) I + 2μ ε. Both equal the generic
// BB path (corotated_element.h) at degree 1; a unit test checks it.
//
// Arrays: x 4x3 corner positions, grad 4x3 rest gradients, quat (w,x,y,z) the rotation warm
// start (in) and result (out), force 4x3 (written), blocks 16 3x3 row-major blocks in
// (a, b) order (written). Pure, no allocation.
#pragma once

namespace vp {

void corotateLinearTet(const double x[12], const double grad[12], double volume, double lambda, double mu,
                       double quat[4], double force[12], double blocks[144]);

}  // namespace vp

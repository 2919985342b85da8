// The one deformation gradient per BB element from which corotation takes its rotation.
//
// For degree n the deformation ∇x varies over the element (a polynomial of degree n−1), but
// corotation uses one rotation per element (as the thesis does). We take R from the volume
// average F̄ = (1/V) ∫_T ∇x dV, because:
// - it is the L2-best constant approximation of ∇x over the element, so every control point
//   (not only the corners) contributes, e.g. a quadratic element bent by its edge nodes
//   rotates by its mean rotation rather than by its chord;
// - it is exact for affine motion (F̄ = F when x = F X + t, every degree), so rigid motion
//   gives exactly zero corotated force;
// - it is closed form and as cheap as the linear case: with ∂B^n_α = n Σ_c B^{n−1}_{α−e_c}
//   ∇λ_c and ∫_T B^{n−1}_γ = V / C(n+2, 3) for every γ,
//       F̄ = Σ_c y_c ⊗ ∇λ_c,   y_c = (n / C(n+2, 3)) Σ_{α: α_c >= 1} x_α ,
//   a 3x4 times 4x3 product after one weighted sum per corner (for n = 1: y_c = x_c and
//   F̄ = Ds Dm⁻¹). For n = 2 it equals ∇x at the centroid; for n = 3 it does not, which is
//   why we average rather than sample.
// Array shapes: x N x 3 current node positions (node order of bb_multi_index.h),
// baryGrad 4 x 3 rest ∇λ_c (bbBarycentricGradients), F 3 x 3 row-major, F[3a+j] = ∂x_a/∂X_j.
// Pure, no allocation; degree must be 1..3 (asserted in debug builds).
// The computation is a kernel body (gpu_kernels/bb_element_kernels.h), which reads which
// corners each node's multi-index touches as bit masks.
#pragma once

#include <cstdint>

namespace vp {

void bbAverageDeformationGradient(int degree, const double* x, const double baryGrad[12],
                                  double F[9]);

// Per node of the degree (bb_multi_index.h order), bit c set when the node's α_c >= 1.
const uint8_t* bbNodeCornerMasks(int degree);

}  // namespace vp

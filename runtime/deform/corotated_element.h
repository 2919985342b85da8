// Corotational linear elasticity for one element (Müller & Gross 2004): the rest stiffness
// K_e acts in the element's unrotated frame, so the force and stiffness are
//   f_e = −R K_e (Rᵀ x − x0),      K_rot = R K_e Rᵀ  (block-wise: R K_αβ Rᵀ).
// Rigid motion x = R x0 + t gives Rᵀ x − x0 = Rᵀ t, a translation, which K_e annihilates,
// so the force is zero for any rotation angle — the reason for corotation.
//
// With the stored rest K_e these are the references the step's kernels are tested against:
// the step applies K_e without storing it (gpu_kernels/bb_element_kernels.h: bbStiffnessApply,
// corotateBBElement) and sums R K Rᵀ from gradient pairs (bb_rotated_stiffness.h).
//
// Array shapes (N = node count, 4/10/20): stiffness 3N x 3N row-major (bb_element_matrices.h
// layout), restPositions/positions/force N x 3, R 3 x 3 row-major, rotatedStiffness 3N x 3N.
#pragma once

namespace vp {

// force = −R K_e (Rᵀ x − x0). nodeCount must be 1..kBBMaxNodes (asserted in debug builds).
void corotatedForce(int nodeCount, const double* stiffness, const double* restPositions,
                    const double* positions, const double R[9], double* force);

// rotatedStiffness = R K_e Rᵀ, one 3x3 block per node pair. Output must not alias input.
void corotatedStiffness(int nodeCount, const double* stiffness, const double R[9],
                        double* rotatedStiffness);

}  // namespace vp

// Corotational linear elasticity for one element (Müller & Gross 2004): the rest stiffness
// K_e acts in the element's unrotated frame, so the force and stiffness are
//   f_e = −R K_e (Rᵀ x − x0),      K_rot = R K_e Rᵀ  (block-wise: R K_αβ Rᵀ).
// Rigid motion x = R x0 + t gives Rᵀ x − x0 = Rᵀ t, a translation, which K_e annihilates,
// so the force is zero for any rotation angle — the reason for corotation.
//
// Array shapes (N = node count, 4/10/20): stiffness 3N x 3N row-major (bb_element_matrices.h
// layout), restPositions/positions/force N x 3, R 3 x 3 row-major, rotatedStiffness 3N x 3N.
// Pure per-element kernels: no allocation (N <= kBBMaxNodes scratch lives on the stack),
// so they can run inside parallel_for and be ported to CUDA as they are.
#pragma once

namespace vp {

// force = −R K_e (Rᵀ x − x0). nodeCount must be 1..kBBMaxNodes (asserted in debug builds).
void corotatedForce(int nodeCount, const double* stiffness, const double* restPositions,
                    const double* positions, const double R[9], double* force);

// rotatedStiffness = R K_e Rᵀ, one 3x3 block per node pair. Output must not alias input.
void corotatedStiffness(int nodeCount, const double* stiffness, const double R[9],
                        double* rotatedStiffness);

// block += sR · K_ab Rᵀ for the node pair (a, b), sR = scale · R (the caller scales R once
// per element): the assembly rotates each block as it adds it, so the rotated 3N x 3N
// matrix is never stored (for cubic elements that buffer was 29 KB per element written and
// read back every step). Inline: it runs once per block of every element, every step.
inline void addRotatedStiffnessBlock(int nodeCount, const double* stiffness, const double R[9],
                                     const double sR[9], int a, int b, double block[9]) {
  const int dim = 3 * nodeCount;
  const double* k0 = stiffness + (3 * a) * dim + 3 * b;
  const double* k1 = k0 + dim;
  const double* k2 = k1 + dim;
  // t = K_ab Rᵀ (row r of K_ab dotted with row c of R), then sR t.
  double t[9];
  for (int c = 0; c < 3; ++c) {
    const double* rc = R + 3 * c;
    t[c] = k0[0] * rc[0] + k0[1] * rc[1] + k0[2] * rc[2];
    t[3 + c] = k1[0] * rc[0] + k1[1] * rc[1] + k1[2] * rc[2];
    t[6 + c] = k2[0] * rc[0] + k2[1] * rc[1] + k2[2] * rc[2];
  }
  for (int r = 0; r < 3; ++r) {
    const double* s = sR + 3 * r;
    for (int c = 0; c < 3; ++c) block[3 * r + c] += s[0] * t[c] + s[1] * t[3 + c] + s[2] * t[6 + c];
  }
}

}  // namespace vp

// Rest-state matrices of one BB tetrahedral element of degree 1..3 (linear elasticity),
// integrated analytically (no quadrature), in double precision because they are computed
// once per element and then only rotated.
//
// Array shapes (N = bbNodeCount(degree), nodes in the order of bb_multi_index.h):
//   restCorners  4 x 3     rest positions X0..X3 of the tet's vertices, row per vertex
//   baryGrad     4 x 3     ∇λ_c, the constant gradients of the barycentric coordinates
//   mass         N x N     scalar M_αβ, row-major; the 3D mass matrix is M ⊗ I3, so the
//                          N x N entries sum to ρV (the 3N x 3N ones to 3ρV)
//   lumpedMass   N         row sums of `mass`
//   stiffness    3N x 3N   row-major; the 3x3 block of node pair (α, β) is rows 3α..3α+2,
//                          columns 3β..3β+2, entry (a, b) couples coordinate a of α with
//                          coordinate b of β
#pragma once

#include "core/status.h"

namespace vp {

// Barycentric gradients and volume of a rest tet. Fails with InvalidArgument when a
// coordinate is not finite, when the tet is inverted (negative signed volume: swap two
// vertices) or degenerate (volume below 1e-10 · (longest edge)³, i.e. flat or a sliver
// whose stiffness would be numerically meaningless).
Status bbBarycentricGradients(const double restCorners[12], double baryGrad[12],
                              double* volume);

// Consistent mass M_αβ = ρ V G_n(α,β) / C(2n+3, 3).
// Fails with InvalidArgument for a bad degree, density <= 0 or not finite, or a bad tet.
Status bbMassMatrix(int degree, const double restCorners[12], double density, double* mass);

// Row-sum lumped mass. Safe for BB elements because every Bernstein basis function is
// non-negative, so each row sum ρ∫B_α is positive; in fact all equal ρV / C(n+3, 3), since
// every degree-n Bernstein polynomial has the same integral. (Row-sum lumping of Lagrange
// quadratic tets gives zero or negative vertex masses instead.)
Status bbLumpedMass(int degree, const double restCorners[12], double density,
                    double* lumpedMass);

// Linear-elastic stiffness with Lamé parameters (lambda, mu):
//   K_αβ^{ab} = (3nV/(4n²−1)) Σ_{c,d} G_{n−1}(α−e_c, β−e_d)
//               · [λ (∇λ_c)_a (∇λ_d)_b + μ (∇λ_c)_b (∇λ_d)_a + μ δ_ab (∇λ_c·∇λ_d)],
// terms whose multi-index has a negative entry dropped. The formula from REFERENCES.md
// was checked against Gauss quadrature of ∫ Bᵀ D B (tests/unit/deform_element_matrices_test).
// Fails with InvalidArgument for a bad degree, a bad tet, or Lamé parameters that are not
// finite or make the material unstable (need mu > 0 and 3·lambda + 2·mu > 0, i.e.
// positive shear and bulk moduli).
Status bbStiffnessMatrix(int degree, const double restCorners[12], double lambda, double mu,
                         double* stiffness);

// Rest position of every node: X_α = Σ_i (α_i / n) X_i. With these control points the
// element's geometry map is the affine rest tet itself (BB form reproduces linear fields).
// Output N x 3. Degree must be 1..3 (InvalidArgument otherwise).
Status bbRestNodePositions(int degree, const double restCorners[12], double* nodePositions);

}  // namespace vp

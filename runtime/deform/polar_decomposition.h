// Rotation R of a 3x3 deformation gradient F (F = R S) for corotational elasticity.
//
// R must stay a proper rotation (det R = +1) for every F the simulation can produce:
// degenerate (rank 0, 1, 2) when an element is crushed, and inverted (det F < 0) when it is
// pushed through itself. A reflection in R would turn the corotated force into one that
// keeps the element inverted; any rotation in R gives a force that pushes it back out.
//
// Two methods, both pure functions over plain arrays (no allocation; matrices row-major,
// M[3*row + col]):
// - polarRotationSvd: the reference, "invertible FEM" style (Irving et al. 2004). SVD
//   F = U Σ Vᵀ; if det(U Vᵀ) < 0 the column of U belonging to the smallest singular value is
//   negated (F then has Σ with its last entry negative, the least-deformation way to read an
//   inverted element); R = U Vᵀ. The result maximizes tr(Rᵀ F) over SO(3).
// - polarRotationIterative: warm-started iteration after Müller et al. 2016, "A robust
//   method to extract the rotational part of deformations": rotate a unit quaternion q by
//   ω until ω vanishes, where ω comes from g = Σ_i r_i × f_i (r_i, f_i the columns of R(q)
//   and F), the gradient of tr(Rᵀ F). Müller et al. take ω = g / |tr(Rᵀ F)|, which converges
//   linearly (~3x per iteration: 25 iterations to 1e-12). We take the Newton step
//   ω = (tr(B) I − sym(B))⁻¹ g, B = F Rᵀ, whenever that matrix is positive definite, and
//   their step otherwise: quadratic convergence, 2–3 iterations to round-off from a warm
//   start within 0.1 rad, 4–9 from any start, for det F > 0. For det F <= 0 it defers to
//   the SVD (see the .cpp). q stays unit length, so R is a rotation even when it stops early.
//   Measured against polarRotationSvd on this 2-core machine (-O2, 200k random F):
//   ~0.75–1.0 µs vs ~1.1–1.6 µs per call with a warm start <= 0.1 rad, equal accuracy.
#pragma once

namespace vp {

// Returns false, and R = identity, when F has a non-finite entry (the caller's divergence
// guard reports it); true otherwise.
bool polarRotationSvd(const double F[9], double R[9]);

// quat: (w, x, y, z), in: the warm start (e.g. the previous frame's rotation of this
// element; (1,0,0,0) for none; need not be normalized but must not be zero), out: the
// result, unit length. R receives its matrix. Iterates until the step |ω| < tolerance
// (radians) or maxIterations. Returns the number of iterations taken (0 when det F <= 0 and
// the SVD answered), or -1 when F is not finite (R = the normalized warm start).
int polarRotationIterative(const double F[9], double quat[4], double R[9], int maxIterations,
                           double tolerance);

// Unit quaternion (w, x, y, z) <-> rotation matrix helpers, for seeding the warm start.
void rotationFromQuaternion(const double quat[4], double R[9]);
void quaternionFromRotation(const double R[9], double quat[4]);

}  // namespace vp

// Evaluation of a BB field of degree 1..3 on one tet, and degree elevation (the
// prolongation of p-multigrid).
//
// These run per render vertex and per multigrid transfer, so they take plain arrays, do
// not allocate and do not validate: `degree` must be 1..3 (checked once where a mesh or
// level is built; a debug build asserts it).
//
// Array shapes (N = bbNodeCount(degree), node order of bb_multi_index.h):
//   bary      4        barycentric coordinates (λ0..λ3); the polynomial is evaluated in its
//                      homogeneous form, so they need not sum to one
//   coeffs    N x 3    control points (node values) of a vector field, row per node
//   baryGrad  4 x 3    ∇λ_c of the rest tet (bbBarycentricGradients)
//   grad      3 x 3    row-major, grad[3i + j] = ∂value_i / ∂X_j
#pragma once

#include "core/status.h"

namespace vp {

// B_α(λ) for every node. Direct sum of the monomials: for n <= 3 it costs fewer flops than
// de Casteljau and is as accurate (all terms are non-negative for λ in the tet).
void bbBasis(int degree, const double bary[4], double* basis /* N */);

// ∂B_α/∂λ_c, output N x 4 row-major. Equals n·B^{n−1}_{α−e_c} (0 when α_c = 0).
void bbBasisBaryDerivatives(int degree, const double bary[4], double* derivatives);

// value = Σ_α coeffs_α B_α(λ).
void bbEvaluate(int degree, const double* coeffs, const double bary[4], double value[3]);

// Spatial gradient of the field at λ: Σ_α coeffs_α ⊗ Σ_c (∂B_α/∂λ_c) ∇λ_c.
void bbEvaluateGradient(int degree, const double* coeffs, const double bary[4],
                        const double baryGrad[12], double grad[9]);

// One row of the per-element elevation operator: the fine (degree n+1) node β takes
// Σ_k weight[k] · coarse[node[k]], k < count.
struct BBElevationRow {
  int count;
  int node[4];
  double weight[4];
};

// Degree elevation n -> n+1: c'_β = Σ_{i: β_i > 0} (β_i/(n+1)) c_{β−e_i}. The result is the
// same polynomial, so the prolongation is exact. A fine node on an edge/face only reads
// coarse nodes on that same edge/face, so neighbouring tets agree on shared nodes and the
// per-element rows assemble into a global prolongation without averaging.
// rows: bbNodeCount(fromDegree + 1) entries. Fails with InvalidArgument unless
// fromDegree is 1 or 2.
Status bbElevationRows(int fromDegree, BBElevationRow* rows);

// Applies the elevation to a field: coarse N(fromDegree) x 3 -> fine N(fromDegree+1) x 3.
// fromDegree must be 1 or 2.
void bbElevate(int fromDegree, const double* coarse, double* fine);

}  // namespace vp

// The per-element kernel bodies of corotational Bernstein–Bézier elements of any degree, which
// a CPU loop and a CUDA thread run alike: the averaged deformation gradient the rotation is
// taken from (runtime/deform/deformation_gradient.h has the derivation), the rest stiffness
// applied without being stored, the corotated force (runtime/deform/corotated_element.h) and
// the rotated stiffness as 16 gradient-pair matrices (runtime/deform/bb_rotated_stiffness.h)
// with its block sums.
//
// Arrays: x, restPositions, u, force N x 3 (node order of runtime/deform/bb_multi_index.h);
// grad 4 x 3 rest barycentric gradients; R 3 x 3 row-major; pairs 16 x 9 (pair c·4+d,
// row-major 3x3); block 3x3 row-major.
#pragma once

#include <cstdint>

#include "gpu_kernels/kernel_support.h"
#include "gpu_kernels/polar_kernels.h"

namespace vp::kernels {

constexpr int kMaxElementNodes = 20;  // nodes of a cubic element

// (n+1)(n+2)(n+3)/6: the nodes of a degree-n element (runtime/deform/bb_multi_index.h).
VP_HOST_DEVICE constexpr int elementNodeCount(int degree) { return (degree + 1) * (degree + 2) * (degree + 3) / 6; }

// F̄ = Σ_c y_c ⊗ ∇λ_c with y_c = (n / C(n+2, 3)) Σ_{α: α_c >= 1} x_α. nodeCorners[k] has bit c
// set when node k's multi-index has α_c >= 1.
VP_HOST_DEVICE inline void bbAverageDeformationGradient(int degree, const uint8_t* nodeCorners, const double* x,
                                                        const double baryGrad[12], double F[9]) {
  const int nodes = elementNodeCount(degree);
  // n / C(n+2, 3): 1, 1/2, 3/10 for n = 1, 2, 3.
  const double weight = degree * 6.0 / (degree * (degree + 1.0) * (degree + 2.0));
  double y[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int k = 0; k < nodes; ++k)
    for (int c = 0; c < 4; ++c)
      if (nodeCorners[k] & (1u << c))
        for (int a = 0; a < 3; ++a) y[c][a] += x[3 * k + a];
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int c = 0; c < 4; ++c) s += y[c][a] * baryGrad[3 * c + j];
      F[3 * a + j] = weight * s;
    }
}

// The structure of a degree-n rest stiffness, for applying K_e without storing it: the
// degree-(n−1) multi-indices γ (lowerCount of them, in runtime/deform/bb_multi_index.h's order;
// the one γ = 0 for n = 1), their Gram factors G_{n−1}(β, γ) (lowerCount², row-major), the node
// of γ + e_d for every (γ, d) (lowerCount × 4), and the index of α_a − e_c for every (node a,
// corner c), −1 where α_a,c = 0 (nodes × 4).
struct BBStiffnessStructureView {
  int lowerCount = 0;
  const double* gram = nullptr;
  const int8_t* raised = nullptr;
  const int8_t* lowered = nullptr;
};

constexpr int kMaxLowerIndices = 10;  // multi-indices of degree 2, those of a cubic element

// Ku = K_e u, sum-factorized. K_ab = s Σ_cd G_{n−1}(α_a−e_c, α_b−e_d) [λ g_c g_dᵀ + μ g_d g_cᵀ +
// μ (g_c·g_d) I] (runtime/deform/bb_element_matrices.h), s = 3nV/(4n²−1), regrouped by
// γ = α_b − e_d: with D_γ = Σ_d u_{γ+e_d} ⊗ g_d and σ(D) = λ tr(D) I + μ (D + Dᵀ),
//   (K u)_a = s Σ_{c: α_a,c ≥ 1} [Σ_γ G_{n−1}(α_a − e_c, γ) σ(D_γ)] g_c,
// a few hundred flops and no 3N x 3N matrix to read (7 KB per quadratic element, 29 KB cubic).
VP_HOST_DEVICE inline void bbStiffnessApply(int degree, const BBStiffnessStructureView& k, const double grad[12],
                                            double volume, double lambda, double mu, const double* u, double* Ku) {
  const int M = k.lowerCount;
  const int N = elementNodeCount(degree);
  double sigma[9 * kMaxLowerIndices];
  for (int g = 0; g < M; ++g) {
    double D[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    for (int d = 0; d < 4; ++d) {
      const double* ud = u + 3 * k.raised[4 * g + d];
      const double* gd = grad + 3 * d;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) D[3 * i + j] += ud[i] * gd[j];
    }
    const double trace = D[0] + D[4] + D[8];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        sigma[9 * g + 3 * i + j] = mu * (D[3 * i + j] + D[3 * j + i]) + (i == j ? lambda * trace : 0.0);
  }
  double S[9 * kMaxLowerIndices];
  for (int b = 0; b < M; ++b) {
    for (int c = 0; c < 9; ++c) S[9 * b + c] = 0.0;
    for (int g = 0; g < M; ++g) {
      const double w = k.gram[M * b + g];
      for (int c = 0; c < 9; ++c) S[9 * b + c] += w * sigma[9 * g + c];
    }
  }
  const double s = 3.0 * degree * volume / (4.0 * degree * degree - 1.0);
  for (int a = 0; a < N; ++a) {
    double f[3] = {0.0, 0.0, 0.0};
    for (int c = 0; c < 4; ++c) {
      const int b = k.lowered[4 * a + c];
      if (b < 0) continue;
      const double* Sb = S + 9 * b;
      const double* gc = grad + 3 * c;
      for (int i = 0; i < 3; ++i) f[i] += Sb[3 * i] * gc[0] + Sb[3 * i + 1] * gc[1] + Sb[3 * i + 2] * gc[2];
    }
    for (int i = 0; i < 3; ++i) Ku[3 * a + i] = s * f[i];
  }
}

// u = Rᵀ x − x0 per node: the element's displacement in its unrotated frame.
VP_HOST_DEVICE inline void unrotatedDisplacement(int nodeCount, const double R[9], const double* x,
                                                 const double* restPositions, double* u) {
  for (int k = 0; k < nodeCount; ++k)
    for (int a = 0; a < 3; ++a) {
      const double* xk = x + 3 * k;
      u[3 * k + a] = R[a] * xk[0] + R[3 + a] * xk[1] + R[6 + a] * xk[2] - restPositions[3 * k + a];
    }
}

// pairs = the 16 P_cd = s V [λ h_c h_dᵀ + μ h_d h_cᵀ + μ (g_c·g_d) I], h = R g,
// s = scale · 3n / (4n² − 1).
VP_HOST_DEVICE inline void bbRotatedGradientPairs(int degree, const double R[9], const double grad[12], double volume,
                                                  double lambda, double mu, double scale, double pairs[144]) {
  const int n = degree;
  const double s = scale * 3.0 * n * volume / (4.0 * n * n - 1.0);
  double h[12];
  for (int c = 0; c < 4; ++c)
    for (int i = 0; i < 3; ++i)
      h[3 * c + i] = R[3 * i] * grad[3 * c] + R[3 * i + 1] * grad[3 * c + 1] + R[3 * i + 2] * grad[3 * c + 2];
  for (int c = 0; c < 4; ++c)
    for (int d = 0; d < 4; ++d) {
      const double* hc = h + 3 * c;
      const double* hd = h + 3 * d;
      const double* gc = grad + 3 * c;
      const double* gd = grad + 3 * d;
      const double shear = mu * (gc[0] * gd[0] + gc[1] * gd[1] + gc[2] * gd[2]);
      double* p = pairs + 9 * (4 * c + d);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          p[3 * i + j] = s * (lambda * hc[i] * hd[j] + mu * hd[i] * hc[j] + (i == j ? shear : 0.0));
    }
}

// The G_{n−1} weights of every node pair (a, b) of a degree: terms of pair (a, b) are
// [start[a·N+b], start[a·N+b+1]), each a gradient pair (c·4+d) and its weight.
struct BBStiffnessTermsView {
  const int32_t* start = nullptr;
  const uint8_t* pair = nullptr;
  const double* weight = nullptr;
};

// block += R K_ab Rᵀ (times the scale the pairs carry).
VP_HOST_DEVICE inline void addBBRotatedBlock(const BBStiffnessTermsView& terms, const double pairs[144], int nodeCount,
                                             int a, int b, double block[9]) {
  const int32_t k = a * nodeCount + b;
  for (int32_t t = terms.start[k]; t < terms.start[k + 1]; ++t) {
    const double w = terms.weight[t];
    const double* p = pairs + 9 * terms.pair[t];
    for (int i = 0; i < 9; ++i) block[i] += w * p[i];
  }
}

// One element's pass of a corotated step: the rotation from the averaged F (warm-started from
// and written to quat), the corotated force −R K_e (Rᵀ x − x0), and the gradient pairs with the
// stiffness scale.
VP_HOST_DEVICE inline void corotateBBElement(int degree, const uint8_t* nodeCorners,
                                             const BBStiffnessStructureView& structure, const double* x,
                                             const double* restPositions, const double grad[12], double volume,
                                             double lambda, double mu, double scale, double quat[4], double* force,
                                             double pairs[144]) {
  const int N = elementNodeCount(degree);
  double F[9], R[9];
  bbAverageDeformationGradient(degree, nodeCorners, x, grad, F);
  // A non-finite F: the identity, and the divergence guard reports the body.
  if (polarRotationIterative(F, quat, R, kCorotationIterations, kCorotationTolerance) < 0)
    for (int i = 0; i < 9; ++i) R[i] = (i % 4 == 0) ? 1.0 : 0.0;
  double u[3 * kMaxElementNodes], Ku[3 * kMaxElementNodes];
  unrotatedDisplacement(N, R, x, restPositions, u);
  bbStiffnessApply(degree, structure, grad, volume, lambda, mu, u, Ku);
  for (int k = 0; k < N; ++k)
    for (int a = 0; a < 3; ++a)
      force[3 * k + a] = -(R[3 * a] * Ku[3 * k] + R[3 * a + 1] * Ku[3 * k + 1] + R[3 * a + 2] * Ku[3 * k + 2]);
  bbRotatedGradientPairs(degree, R, grad, volume, lambda, mu, scale, pairs);
}

}  // namespace vp::kernels

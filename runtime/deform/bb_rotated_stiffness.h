// The rotated stiffness R K_e Rᵀ of a BB element, block by block, without the 3N x 3N matrix.
//
// K_ab = (3nV/(4n²−1)) Σ_{c,d} G_{n−1}(α_a−e_c, α_b−e_d) · [λ g_c g_dᵀ + μ g_d g_cᵀ + μ (g_c·g_d) I]
// (bb_element_matrices.h), so R K_ab Rᵀ is the same sum over the 16 "gradient pair" matrices
// with rotated gradients h = R g (R I Rᵀ = I):
//   P_cd = s V [λ h_c h_dᵀ + μ h_d h_cᵀ + μ (g_c·g_d) I],   R K_ab Rᵀ = Σ G_{n−1}(…) P_cd.
// Per element and step only the 16 P_cd are computed (144 numbers instead of the 900 / 3600
// of a rotated quadratic / cubic K); a block then costs 1 to 9 terms of 9 flops, and the
// assembly no longer reads the stored rest K (7 KB / 29 KB per element) a second time.
//
// The pairs and the block sums are kernel bodies (gpu_kernels/bb_element_kernels.h:
// kernels::bbRotatedGradientPairs, kernels::addBBRotatedBlock); the terms are built here.
#pragma once

#include "core/allocator.h"
#include "gpu_kernels/bb_element_kernels.h"

#include <cstdint>
#include <vector>

namespace vp {

// The G_{n−1} weights of every node pair (a, b) of a degree: terms of pair (a, b) are
// [start[a·N+b], start[a·N+b+1]), each a gradient pair (c·4+d) and its weight.
struct BBStiffnessTerms {
  int degree = 0;
  Array<int32_t> start;
  Array<uint8_t> pair;
  Array<double> weight;

  kernels::BBStiffnessTermsView view() const { return {start.data(), pair.data(), weight.data()}; }
};

// degree must be 1..3.
BBStiffnessTerms bbStiffnessTerms(int degree);

// What kernels::bbStiffnessApply reads to apply a degree's rest K_e without storing it (the
// layout of kernels::BBStiffnessStructureView).
struct BBStiffnessStructure {
  int lowerCount = 0;
  Array<double> gram;
  Array<int8_t> raised;
  Array<int8_t> lowered;

  kernels::BBStiffnessStructureView view() const { return {lowerCount, gram.data(), raised.data(), lowered.data()}; }
};

// degree must be 1..3.
BBStiffnessStructure bbStiffnessStructure(int degree);

}  // namespace vp

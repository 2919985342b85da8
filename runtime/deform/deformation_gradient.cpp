#include "deform/deformation_gradient.h"

#include <array>
#include <cassert>

#include "deform/bb_multi_index.h"
#include "gpu_kernels/bb_element_kernels.h"

namespace vp {

const uint8_t* bbNodeCornerMasks(int degree) {
  assert(degree >= 1 && degree <= kBBMaxDegree);
  static const auto masks = [] {
    std::array<std::array<uint8_t, kBBMaxNodes>, kBBMaxDegree + 1> table{};
    for (int n = 1; n <= kBBMaxDegree; ++n) {
      const BBMultiIndex* nodes = bbMultiIndices(n);
      for (int k = 0; k < bbNodeCount(n); ++k)
        for (int c = 0; c < 4; ++c)
          if (nodes[k].a[c] > 0) table[n][k] |= static_cast<uint8_t>(1u << c);
    }
    return table;
  }();
  return masks[degree].data();
}

void bbAverageDeformationGradient(int degree, const double* x, const double baryGrad[12], double F[9]) {
  kernels::bbAverageDeformationGradient(degree, bbNodeCornerMasks(degree), x, baryGrad, F);
}

}  // namespace vp

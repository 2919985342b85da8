#include "deform/bb_rotated_stiffness.h"

#include <cassert>

#include "deform/bb_multi_index.h"

namespace vp {

BBStiffnessTerms bbStiffnessTerms(int degree) {
  assert(degree >= 1 && degree <= kBBMaxDegree);
  BBStiffnessTerms terms;
  terms.degree = degree;
  const int N = bbNodeCount(degree);
  const BBMultiIndex* nodes = bbMultiIndices(degree);
  terms.start.push_back(0);
  for (int a = 0; a < N; ++a)
    for (int b = 0; b < N; ++b) {
      for (int c = 0; c < 4; ++c) {
        if (nodes[a].a[c] == 0) continue;
        BBMultiIndex lowerA = nodes[a];
        --lowerA.a[c];
        for (int d = 0; d < 4; ++d) {
          if (nodes[b].a[d] == 0) continue;
          BBMultiIndex lowerB = nodes[b];
          --lowerB.a[d];
          terms.pair.push_back(static_cast<uint8_t>(4 * c + d));
          terms.weight.push_back(bbGramFactor(lowerA, lowerB));
        }
      }
      terms.start.push_back(static_cast<int32_t>(terms.pair.size()));
    }
  return terms;
}

}  // namespace vp

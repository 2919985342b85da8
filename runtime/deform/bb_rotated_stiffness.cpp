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

BBStiffnessStructure bbStiffnessStructure(int degree) {
  assert(degree >= 1 && degree <= kBBMaxDegree);
  BBStiffnessStructure k;
  const int N = bbNodeCount(degree);
  const BBMultiIndex* nodes = bbMultiIndices(degree);
  // The degree-(n−1) multi-indices: the table's, or the single γ = 0 below degree 1.
  const BBMultiIndex zero{{0, 0, 0, 0}};
  const BBMultiIndex* lower = degree > 1 ? bbMultiIndices(degree - 1) : &zero;
  k.lowerCount = degree > 1 ? bbNodeCount(degree - 1) : 1;
  const auto lowerIndex = [&](const int alpha[4]) { return degree > 1 ? bbNodeIndex(alpha) : 0; };
  for (int b = 0; b < k.lowerCount; ++b)
    for (int g = 0; g < k.lowerCount; ++g) k.gram.push_back(bbGramFactor(lower[b], lower[g]));
  for (int g = 0; g < k.lowerCount; ++g)
    for (int d = 0; d < 4; ++d) {
      int alpha[4] = {lower[g].a[0], lower[g].a[1], lower[g].a[2], lower[g].a[3]};
      ++alpha[d];
      k.raised.push_back(static_cast<int8_t>(bbNodeIndex(alpha)));
    }
  for (int a = 0; a < N; ++a)
    for (int c = 0; c < 4; ++c) {
      int alpha[4] = {nodes[a].a[0], nodes[a].a[1], nodes[a].a[2], nodes[a].a[3]};
      if (alpha[c] == 0) {
        k.lowered.push_back(-1);
        continue;
      }
      --alpha[c];
      k.lowered.push_back(static_cast<int8_t>(lowerIndex(alpha)));
    }
  return k;
}

}  // namespace vp

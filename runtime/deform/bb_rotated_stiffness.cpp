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

void bbRotatedGradientPairs(int degree, const double R[9], const double grad[12], double volume, double lambda,
                            double mu, double scale, double pairs[144]) {
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
        for (int j = 0; j < 3; ++j) p[3 * i + j] = s * (lambda * hc[i] * hd[j] + mu * hd[i] * hc[j] + (i == j ? shear : 0.0));
    }
}

}  // namespace vp

#include "deform/deformation_gradient.h"

#include <cassert>

#include "deform/bb_multi_index.h"

namespace vp {

void bbAverageDeformationGradient(int degree, const double* x, const double baryGrad[12],
                                  double F[9]) {
  assert(degree >= 1 && degree <= kBBMaxDegree);
  const BBMultiIndex* nodes = bbMultiIndices(degree);
  // n / C(n+2, 3): 1, 1/2, 3/10 for n = 1, 2, 3.
  const double weight = degree * 6.0 / (degree * (degree + 1.0) * (degree + 2.0));
  double y[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int k = 0; k < bbNodeCount(degree); ++k)
    for (int c = 0; c < 4; ++c)
      if (nodes[k].a[c] > 0)
        for (int a = 0; a < 3; ++a) y[c][a] += x[3 * k + a];
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int c = 0; c < 4; ++c) s += y[c][a] * baryGrad[3 * c + j];
      F[3 * a + j] = weight * s;
    }
}

}  // namespace vp

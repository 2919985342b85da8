#include "deform/corotated_element.h"

#include <cassert>

#include "deform/bb_multi_index.h"

namespace vp {

void corotatedStiffness(int nodeCount, const double* stiffness, const double R[9],
                        double* rotatedStiffness) {
  assert(nodeCount >= 1 && nodeCount <= kBBMaxNodes);
  const int dim = 3 * nodeCount;
  for (int i = 0; i < nodeCount; ++i)
    for (int j = 0; j < nodeCount; ++j) {
      // t = K_ij Rᵀ, then R t.
      double t[9];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const double* k = stiffness + (3 * i + a) * dim + 3 * j;
          t[3 * a + b] = k[0] * R[3 * b] + k[1] * R[3 * b + 1] + k[2] * R[3 * b + 2];
        }
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          rotatedStiffness[(3 * i + a) * dim + 3 * j + b] =
              R[3 * a] * t[b] + R[3 * a + 1] * t[3 + b] + R[3 * a + 2] * t[6 + b];
    }
}

}  // namespace vp

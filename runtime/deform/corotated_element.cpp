#include "deform/corotated_element.h"

#include <cassert>

#include "deform/bb_multi_index.h"

namespace vp {

void corotatedForce(int nodeCount, const double* stiffness, const double* restPositions,
                    const double* positions, const double R[9], double* force) {
  assert(nodeCount >= 1 && nodeCount <= kBBMaxNodes);
  const int dim = 3 * nodeCount;
  // Unrotated displacement u = Rᵀ x − x0, computed once per node rather than per block.
  double u[3 * kBBMaxNodes];
  for (int k = 0; k < nodeCount; ++k)
    for (int a = 0; a < 3; ++a) {
      const double* x = positions + 3 * k;
      u[3 * k + a] = R[a] * x[0] + R[3 + a] * x[1] + R[6 + a] * x[2] - restPositions[3 * k + a];
    }
  for (int k = 0; k < nodeCount; ++k) {
    double g[3];
    for (int a = 0; a < 3; ++a) {
      const double* row = stiffness + (3 * k + a) * dim;
      double s = 0.0;
      for (int j = 0; j < dim; ++j) s += row[j] * u[j];
      g[a] = s;
    }
    for (int a = 0; a < 3; ++a)
      force[3 * k + a] = -(R[3 * a] * g[0] + R[3 * a + 1] * g[1] + R[3 * a + 2] * g[2]);
  }
}

void corotatedStiffness(int nodeCount, const double* stiffness, const double R[9],
                        double* rotatedStiffness) {
  assert(nodeCount >= 1 && nodeCount <= kBBMaxNodes);
  const int dim = 3 * nodeCount;
  for (int i = 0; i < nodeCount; ++i)
    for (int j = 0; j < nodeCount; ++j) {
      double block[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      addRotatedStiffnessBlock(nodeCount, stiffness, R, R, i, j, block);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rotatedStiffness[(3 * i + r) * dim + 3 * j + c] = block[3 * r + c];
    }
}

}  // namespace vp

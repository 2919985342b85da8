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

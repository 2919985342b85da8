// Shared fixtures of the deform unit tests: reproducible random tets and matrices.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "deform/deformable_body.h"
#include "linalg/block_sparse_matrix.h"
#include "linalg/node_prolongation.h"
#include "random_values.h"

namespace vp::deform_test {

// A random, non-degenerate, positively oriented tet: a jittered reference tet, scaled,
// rotated and moved, so tests never rely on axis-aligned edges or unit size.
inline void randomTet(std::mt19937& rng, double corners[12]) {
  std::uniform_real_distribution<double> jitter(-0.25, 0.25);
  std::uniform_real_distribution<double> scale(0.3, 3.0);
  std::uniform_real_distribution<double> offset(-5.0, 5.0);
  const double ref[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::normal_distribution<double> normal;
  const Eigen::Matrix3d rot = testing_values::randomQuaternion(normal, rng).toRotationMatrix();
  const double s = scale(rng);
  const Eigen::Vector3d t = testing_values::randomVector(offset, rng);
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector3d p =
        Eigen::Vector3d(ref[3 * i], ref[3 * i + 1], ref[3 * i + 2]) + testing_values::randomVector(jitter, rng);
    p = rot * (s * p) + t;
    for (int a = 0; a < 3; ++a) corners[3 * i + a] = p[a];
  }
}

inline Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return testing_values::randomQuaternion(n, rng).toRotationMatrix();
}

inline Eigen::Matrix3d randomMatrix(std::mt19937& rng, double lo = -1.0, double hi = 1.0) {
  std::uniform_real_distribution<double> u(lo, hi);
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = u(rng);
  return m;
}

// Random barycentric coordinates, uniform on the tet (sorted-uniform spacing).
inline void randomBary(std::mt19937& rng, double bary[4]) {
  std::exponential_distribution<double> e(1.0);
  double s = 0.0;
  for (int i = 0; i < 4; ++i) s += (bary[i] = e(rng));
  for (int i = 0; i < 4; ++i) bary[i] /= s;
}

// Pins every node whose rest x is exactly `x` (a clamped face of a box mesh).
inline void pinNodesAtX(DeformableBody& body, double x) {
  std::vector<int32_t> nodes;
  for (int32_t i = 0; i < body.nodeCount(); ++i)
    if (body.restPositions()[3 * i] == x) nodes.push_back(i);
  body.setPinned(nodes.data(), static_cast<int64_t>(nodes.size()), true);
}

// Dense copies of a block matrix and of a per-node prolongation (3 rows per fine node, 3
// columns per coarse node), for checking operators against explicit products.
inline Eigen::MatrixXd denseMatrix(const BlockSparseMatrix<double>& m) {
  using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3 * m.blockRows, 3 * m.blockRows);
  for (int32_t r = 0; r < m.blockRows; ++r)
    for (int32_t k = m.rowStart[r]; k < m.rowStart[r + 1]; ++k)
      d.block<3, 3>(3 * r, 3 * m.columns[k]) = Eigen::Map<const Mat3R>(&m.values[9 * static_cast<int64_t>(k)]);
  return d;
}

inline Eigen::MatrixXd denseProlongation(const NodeProlongation& P) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3 * P.fineNodes, 3 * P.coarseNodes);
  for (int32_t i = 0; i < P.fineNodes; ++i)
    for (int32_t k = P.rowStart[i]; k < P.rowStart[i + 1]; ++k)
      d.block<3, 3>(3 * i, 3 * P.columns[k]) = P.weights[k] * Eigen::Matrix3d::Identity();
  return d;
}

}  // namespace vp::deform_test

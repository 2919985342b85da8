#include "geometry/bcc_lattice.h"

namespace vp {

BccLattice::BccLattice(const Eigen::Vector3d& origin, double h, const std::array<int64_t, 3>& cubes)
    : origin_(origin), h_(h), cubes_(cubes) {}

LatticePoint BccLattice::point(int64_t id) const {
  const bool corner = id < cornerCount();
  const int64_t local = corner ? id : id - cornerCount();
  const int64_t nx = corner ? cubes_[0] + 1 : cubes_[0], ny = corner ? cubes_[1] + 1 : cubes_[1];
  const int64_t odd = corner ? 0 : 1;
  return {{2 * (local % nx) + odd, 2 * ((local / nx) % ny) + odd, 2 * (local / (nx * ny)) + odd}};
}

int64_t BccLattice::id(const LatticePoint& d) const {
  const int64_t odd = d[0] & 1;
  for (int k = 0; k < 3; ++k)
    if (d[k] < 0 || d[k] > 2 * cubes_[k] || (d[k] & 1) != odd) return -1;
  if (odd == 0) return (d[2] / 2 * (cubes_[1] + 1) + d[1] / 2) * (cubes_[0] + 1) + d[0] / 2;
  return cornerCount() + ((d[2] / 2) * cubes_[1] + d[1] / 2) * cubes_[0] + d[0] / 2;
}

Eigen::Vector3d BccLattice::position(const LatticePoint& d) const {
  return origin_ + h_ * Eigen::Vector3d(0.5 * double(d[0]), 0.5 * double(d[1]), 0.5 * double(d[2]));
}

}  // namespace vp

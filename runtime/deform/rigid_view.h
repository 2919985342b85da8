// A body of nodes seen as a rigid body: its mass, centre of mass, inertia about it, momentum
// and angular momentum (x and v 3 per node, masses 1 per node).
#pragma once

#include <Eigen/Dense>

#include "core/allocator.h"
#include "core/math_types.h"

namespace vp {

struct RigidView {
  double mass = 0.0;
  Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero(), angularMomentum = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();

  static Vec3 at(const Array<double>& a, size_t node) { return Vec3(a[3 * node], a[3 * node + 1], a[3 * node + 2]); }

  // v may be null (no momenta).
  RigidView(const Array<double>& x, const Array<double>* v, const Array<double>& m) {
    for (size_t i = 0; i < m.size(); ++i) mass += m[i], centre += m[i] * at(x, i);
    if (!(mass > 0.0)) return;
    centre /= mass;
    for (size_t i = 0; i < m.size(); ++i) {
      const Vec3 r = at(x, i) - centre;
      inertia += m[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
      if (v == nullptr) continue;
      momentum += m[i] * at(*v, i);
      angularMomentum += m[i] * r.cross(at(*v, i));
    }
  }
  // I^-1 b; zero where the inertia is singular (a body of collinear nodes cannot spin).
  Vec3 solveInertia(const Vec3& b) const {
    Vec3 out = Vec3::Zero();
    solve(inertia, b, &out);
    return out;
  }
  // The same for any inertia; false (and *out untouched) where it is singular.
  static bool solve(const Eigen::Matrix3d& I, const Vec3& b, Vec3* out) {
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(I);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-12 * I.trace())) return false;
    *out = ldlt.solve(b);
    return true;
  }
};

}  // namespace vp

// Shared helpers for the fluid face-coverage tests: random poses, independent inside
// predicates (written from the shape definitions, not from the code under test) and
// supersampled reference coverage.
#pragma once

#include "collide/face_coverage.h"
#include "random_values.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace vp {
namespace testutil {

inline Eigen::Quaterniond randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return testing_values::randomQuaternion(g, rng);
}

// Inside test in the shape's local frame, from the definitions in collider_shape.h.
inline bool insideLocal(const ColliderShape& s, const Eigen::Vector3d& p) {
  switch (s.kind) {
    case ShapeKind::Sphere: return p.squaredNorm() <= s.radius * s.radius;
    case ShapeKind::Box: return (p.cwiseAbs() - s.halfExtents).maxCoeff() <= 0.0;
    case ShapeKind::Capsule: {
      const double y = std::max(-s.halfHeight, std::min(s.halfHeight, p.y()));
      return (p - Eigen::Vector3d(0, y, 0)).squaredNorm() <= s.radius * s.radius;
    }
    case ShapeKind::Cylinder:
      return std::fabs(p.y()) <= s.halfHeight && p.x() * p.x() + p.z() * p.z() <= s.radius * s.radius;
    case ShapeKind::Plane: return s.planeNormal.dot(p) <= s.planeOffset;
    default: return false;
  }
}

inline bool insideWorld(const ColliderShape& s, const Eigen::Vector3d& x) {
  return insideLocal(s, s.rotation.normalized().conjugate() * (x - s.translation));
}

// Midpoint-rule supersampling of the covered fraction on an n x n grid of sub-squares.
template <class Inside>
double supersample(const AxisFace& f, int n, const Inside& inside) {
  const int a1 = (f.axis + 1) % 3, a2 = (f.axis + 2) % 3;
  long hits = 0;
  Eigen::Vector3d x = f.centre;
  for (int j = 0; j < n; ++j) {
    x[a2] = f.centre[a2] + f.h * ((j + 0.5) / n - 0.5);
    for (int i = 0; i < n; ++i) {
      x[a1] = f.centre[a1] + f.h * ((i + 0.5) / n - 0.5);
      hits += inside(x) ? 1 : 0;
    }
  }
  return static_cast<double>(hits) / (static_cast<double>(n) * n);
}

inline AxisFace unitFace(int axis, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero(),
                         double h = 1.0) {
  AxisFace f;
  f.axis = axis;
  f.centre = centre;
  f.h = h;
  return f;
}

}  // namespace testutil
}  // namespace vp

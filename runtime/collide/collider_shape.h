// ColliderShape: a plain description of one rigid solid as the fluid sees it, independent of
// Bullet. The collide/ module fills it from a btCollisionShape and the body's state; the fluid
// only reads it (face fractions, solid velocities).
//
// Conventions (match Bullet's shapes):
//   - local frame: the shape is centred at the local origin;
//     capsule / cylinder axis is local Y, `halfHeight` is half the length of the axis part
//     (capsule: the segment between the two sphere centres; cylinder: half its height),
//     like btCapsuleShape(radius, 2*halfHeight) and btCylinderShape(r, halfHeight, r);
//   - pose: world = rotation * local + translation;
//   - velocity of a solid point x: linearVelocity + angularVelocity x (x - translation),
//     i.e. `translation` is the body's centre of mass;
//   - half-space plane: the solid is { x_local : planeNormal . x_local <= planeOffset }
//     (normal need not be unit; it is normalized when the shape is prepared);
//   - convex hull: the hull of `hullPoints` (local), at least 4 non-coplanar points;
//   - triangle mesh: closed, watertight, consistently oriented (either way round:
//     an inward-oriented mesh is flipped when prepared), `meshVertices` local.
#pragma once

#include "core/allocator.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace vp {

enum class ShapeKind : int {
  Sphere = 0,
  Box = 1,
  Capsule = 2,
  Cylinder = 3,
  Plane = 4,       // half-space
  ConvexHull = 5,
  TriangleMesh = 6,
};

const char* shapeKindName(ShapeKind kind);

struct ColliderShape {
  ShapeKind kind = ShapeKind::Sphere;

  // Parameters; only those of `kind` are read.
  double radius = 0.5;                                     // sphere, capsule, cylinder
  Eigen::Vector3d halfExtents = Eigen::Vector3d(0.5, 0.5, 0.5);  // box
  double halfHeight = 0.5;                                 // capsule, cylinder (local Y)
  Eigen::Vector3d planeNormal = Eigen::Vector3d(0, 1, 0);  // plane
  double planeOffset = 0.0;                                // plane
  Array<Eigen::Vector3d> hullPoints;                 // convex hull
  Array<Eigen::Vector3d> meshVertices;               // triangle mesh
  Array<Eigen::Vector3i> meshTriangles;              // triangle mesh, indices

  // Rigid pose and velocity.
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();

  void setRotationMatrix(const Eigen::Matrix3d& r) { rotation = Eigen::Quaterniond(r); }
};

}  // namespace vp

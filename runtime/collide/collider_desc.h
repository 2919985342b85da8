// Plain description of a rigid collider: what the C ABI and scene files create, and what the
// fluid (face fractions) and deformables (contacts) read back as exact geometry. Independent
// of Bullet so that geometry queries never depend on Bullet's collision margins.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/allocator.h"
#include "core/collision_filter.h"
#include "core/math_types.h"
#include "core/status.h"

namespace vp {

enum class BodyType : int { Static = 0, Kinematic = 1, Dynamic = 2 };

enum class ShapeType : int { Sphere = 0, Box = 1, Capsule = 2, Cylinder = 3, Plane = 4, ConvexHull = 5, TriangleMesh = 6 };

const char* shapeTypeName(ShapeType type);
const char* bodyTypeName(BodyType type);

struct ShapeDesc {
  ShapeType type = ShapeType::Sphere;
  double radius = 0.5;
  double halfHeight = 0.5;            // capsule/cylinder, along local Y
  Vec3 halfExtents{0.5, 0.5, 0.5};    // box
  Vec3 normal{0.0, 1.0, 0.0};         // plane: dot(normal, x) <= offset is solid
  double offset = 0.0;
  Array<Vec3> points;           // convex hull points or mesh vertices (scaled)
  Array<std::array<int32_t, 3>> triangles;
  std::string meshFile;               // resolved into points/triangles by validation
  Vec3 meshScale{1.0, 1.0, 1.0};
};

struct ColliderDesc {
  std::string name;                   // optional, from scene files
  BodyType bodyType = BodyType::Static;
  ShapeDesc shape;
  Pose pose;
  Vec3 linearVelocity = Vec3::Zero();
  Vec3 angularVelocity = Vec3::Zero();
  double mass = 1.0;
  double friction = 0.5;
  double restitution = 0.0;
  double linearDamping = 0.0;
  double angularDamping = 0.05;
  CollisionFilter filter;  // which rigid bodies, deformables and fluids it meets
  // Dynamic: starts asleep, at rest, until something wakes it (a touch, a load, the host).
  bool sleeping = false;
  void* userData = nullptr;
};

// What a host may change on a body after creation (vpColliderSetProperties); the same fields
// of ColliderDesc. `mass` matters for dynamic bodies only.
struct BodyProperties {
  double mass = 1.0;
  double friction = 0.5;
  double restitution = 0.0;
  double linearDamping = 0.0;
  double angularDamping = 0.05;
};
BodyProperties bodyPropertiesOf(const ColliderDesc& desc);
// The one check of these fields, for creation and for run-time changes; messages name them as
// in vpColliderDef ("mass = 0: ...").
Status validateBodyProperties(BodyType bodyType, const BodyProperties& properties);

// Checks every field (messages name the field as in vpColliderDef, e.g. "shape.radius"),
// normalizes the plane normal and the rotation, and loads `shape.meshFile` into
// points/triangles with assimp. On failure `desc` is unchanged.
Status validateColliderDesc(ColliderDesc& desc);

}  // namespace vp

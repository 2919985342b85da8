#include <cmath>

#include "collide/collider_desc.h"
#include "core/physical_limits.h"
#include "geometry/surface_mesh.h"

namespace vp {
namespace {

Status checkVec(const char* field, const Vec3& v) {
  if (!v.allFinite())
    return fail(Status::InvalidArgument, "%s = (%g, %g, %g): must be finite", field, v.x(), v.y(), v.z());
  return Status::Ok;
}

Status checkRange(const char* field, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi))  // also rejects NaN
    return fail(Status::InvalidArgument, "%s = %g: must be in [%g, %g]", field, value, lo, hi);
  return Status::Ok;
}

Status checkPoints(const Array<Vec3>& points) {
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      return fail(Status::InvalidArgument, "shape.points[%zu] = (%g, %g, %g): must be finite", i, points[i].x(),
                  points[i].y(), points[i].z());
  return Status::Ok;
}

// A hull needs points spanning 3D; a flat one has no volume for the fluid or for Bullet's
// inertia.
Status checkSpans3D(const Array<Vec3>& points) {
  if (points.size() < 4)
    return fail(Status::InvalidArgument, "shape.pointCount = %zu: a convex hull needs at least 4 points",
                points.size());
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double scale = (hi - lo).norm();
  const double eps = 1e-9 * scale;
  size_t b = 0, c = 0;
  for (size_t i = 1; i < points.size() && !b; ++i)
    if ((points[i] - points[0]).norm() > eps) b = i;
  Vec3 n = Vec3::Zero();
  for (size_t i = 1; i < points.size() && b && !c; ++i) {
    n = (points[b] - points[0]).cross(points[i] - points[0]);
    if (n.norm() > eps * scale) c = i;
  }
  if (b && c) {
    n.normalize();
    for (const Vec3& p : points)
      if (std::abs(n.dot(p - points[0])) > eps) return Status::Ok;
  }
  return fail(Status::InvalidArgument, "shape.points: the %zu points are coplanar; a convex hull needs volume",
              points.size());
}

Status validateShape(ShapeDesc& shape, BodyType bodyType) {
  switch (shape.type) {
    case ShapeType::Sphere:
      return checkLength("shape.radius", shape.radius);
    case ShapeType::Box:
      VP_TRY(checkLength("shape.halfExtents.x", shape.halfExtents.x()));
      VP_TRY(checkLength("shape.halfExtents.y", shape.halfExtents.y()));
      return checkLength("shape.halfExtents.z", shape.halfExtents.z());
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
      VP_TRY(checkLength("shape.radius", shape.radius));
      return checkLength("shape.halfHeight", shape.halfHeight);
    case ShapeType::Plane: {
      if (bodyType == BodyType::Dynamic)
        return fail(Status::InvalidArgument, "shape.type = plane: a plane cannot be a dynamic body");
      VP_TRY(checkVec("shape.normal", shape.normal));
      if (shape.normal.norm() < 1e-6)
        return fail(Status::InvalidArgument, "shape.normal = (%g, %g, %g): must not be zero", shape.normal.x(),
                    shape.normal.y(), shape.normal.z());
      if (!std::isfinite(shape.offset))
        return fail(Status::InvalidArgument, "shape.offset = %g: must be finite", shape.offset);
      return Status::Ok;
    }
    case ShapeType::ConvexHull:
    case ShapeType::TriangleMesh:
      break;
  }
  VP_TRY(checkVec("shape.meshScale", shape.meshScale));
  for (int i = 0; i < 3; ++i)
    if (shape.meshScale[i] == 0.0)
      return fail(Status::InvalidArgument, "shape.meshScale = (%g, %g, %g): components must not be zero",
                  shape.meshScale.x(), shape.meshScale.y(), shape.meshScale.z());
  if (shape.points.empty() && !shape.meshFile.empty()) {
    SurfaceMesh mesh;
    Status loaded = loadSurfaceMesh(shape.meshFile, &mesh);
    if (!ok(loaded)) return addErrorContext(loaded, "shape.meshFile");
    shape.points = std::move(mesh.vertices);
    if (shape.type == ShapeType::TriangleMesh) shape.triangles = std::move(mesh.triangles);
  }
  // Bake the scale so every consumer (Bullet, face fractions, contacts) sees one geometry.
  for (Vec3& p : shape.points) p = p.cwiseProduct(shape.meshScale);
  shape.meshScale = Vec3::Ones();
  if (shape.points.empty())
    return fail(Status::InvalidArgument, "shape.points = NULL and shape.meshFile empty: %s needs vertices",
                shapeTypeName(shape.type));
  VP_TRY(checkPoints(shape.points));
  if (shape.type == ShapeType::ConvexHull) return checkSpans3D(shape.points);
  if (bodyType == BodyType::Dynamic)
    return fail(Status::Unsupported,
                "shape.type = triangleMesh with bodyType = dynamic: use a convex hull for moving bodies");
  if (shape.triangles.empty())
    return fail(Status::InvalidArgument, "shape.triangleCount = 0: a triangle mesh needs triangles");
  const int32_t n = static_cast<int32_t>(shape.points.size());
  for (size_t t = 0; t < shape.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (shape.triangles[t][k] < 0 || shape.triangles[t][k] >= n)
        return fail(Status::InvalidArgument, "shape.indices[%zu] = %d: out of range [0, %d)", t * 3 + k,
                    shape.triangles[t][k], n);
  return Status::Ok;
}

}  // namespace

const char* shapeTypeName(ShapeType type) {
  static const char* const names[] = {"sphere", "box", "capsule", "cylinder", "plane", "convexHull", "triangleMesh"};
  int i = static_cast<int>(type);
  return i >= 0 && i < 7 ? names[i] : "unknown";
}

const char* bodyTypeName(BodyType type) {
  static const char* const names[] = {"static", "kinematic", "dynamic"};
  int i = static_cast<int>(type);
  return i >= 0 && i < 3 ? names[i] : "unknown";
}

BodyProperties bodyPropertiesOf(const ColliderDesc& desc) {
  return BodyProperties{desc.mass, desc.friction, desc.restitution, desc.linearDamping, desc.angularDamping};
}

Status validateBodyProperties(BodyType bodyType, const BodyProperties& p) {
  if (bodyType == BodyType::Dynamic) VP_TRY(checkMass("mass", p.mass));
  VP_TRY(checkRange("friction", p.friction, 0.0, 1e3));
  VP_TRY(checkRange("restitution", p.restitution, 0.0, 1.0));
  VP_TRY(checkRange("linearDamping", p.linearDamping, 0.0, 1.0));
  VP_TRY(checkRange("angularDamping", p.angularDamping, 0.0, 1.0));
  return Status::Ok;
}

Status validateColliderDesc(ColliderDesc& in) {
  ColliderDesc desc = in;  // work on a copy: a failure leaves the caller's desc unchanged
  int bodyType = static_cast<int>(desc.bodyType);
  if (bodyType < 0 || bodyType > 2) return fail(Status::InvalidArgument, "bodyType = %d: unknown body type", bodyType);
  int shapeType = static_cast<int>(desc.shape.type);
  if (shapeType < 0 || shapeType > 6) return fail(Status::InvalidArgument, "shape.type = %d: unknown shape type", shapeType);
  VP_TRY(checkPose("pose", &desc.pose));
  VP_TRY(checkLinearVelocity("linearVelocity", desc.linearVelocity));
  VP_TRY(checkAngularVelocity("angularVelocity", desc.angularVelocity));
  if (desc.bodyType == BodyType::Static && (desc.linearVelocity.squaredNorm() > 0 || desc.angularVelocity.squaredNorm() > 0))
    return fail(Status::InvalidArgument, "linearVelocity/angularVelocity: a static body cannot move");
  if (desc.sleeping && desc.bodyType != BodyType::Dynamic)
    return fail(Status::InvalidArgument, "sleeping: only a dynamic body sleeps");
  if (desc.sleeping && (desc.linearVelocity.squaredNorm() > 0 || desc.angularVelocity.squaredNorm() > 0))
    return fail(Status::InvalidArgument, "sleeping: a body that starts asleep starts at rest (linearVelocity and "
                "angularVelocity must be 0)");
  VP_TRY(validateBodyProperties(desc.bodyType, bodyPropertiesOf(desc)));
  VP_TRY(validateShape(desc.shape, desc.bodyType));
  if (desc.shape.type == ShapeType::Plane) desc.shape.normal.normalize();
  in = std::move(desc);
  return Status::Ok;
}

}  // namespace vp

// Validation of a ColliderShape and its world-space preparation (planes, mesh BVH, bounds).
#include "collide/face_coverage_detail.h"
#include "geometry/closed_surface.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace vp {

const char* shapeKindName(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::Sphere: return "sphere";
    case ShapeKind::Box: return "box";
    case ShapeKind::Capsule: return "capsule";
    case ShapeKind::Cylinder: return "cylinder";
    case ShapeKind::Plane: return "plane";
    case ShapeKind::ConvexHull: return "convexHull";
    case ShapeKind::TriangleMesh: return "triangleMesh";
  }
  return "unknown";
}

namespace {

constexpr double kHuge = 1e30;

bool finite3(const Eigen::Vector3d& v) { return v.allFinite(); }

Status validateShape(const ColliderShape& s) {
  const char* k = shapeKindName(s.kind);
  if (!finite3(s.translation))
    return fail(Status::InvalidArgument, "%s: translation is not finite", k);
  if (!s.rotation.coeffs().allFinite() || !(s.rotation.norm() > 1e-12))
    return fail(Status::InvalidArgument, "%s: rotation quaternion is not finite or is zero", k);
  if (!finite3(s.linearVelocity) || !finite3(s.angularVelocity))
    return fail(Status::InvalidArgument, "%s: linearVelocity/angularVelocity not finite", k);
  switch (s.kind) {
    case ShapeKind::Sphere:
    case ShapeKind::Capsule:
    case ShapeKind::Cylinder:
      if (!std::isfinite(s.radius) || !(s.radius > 0.0))
        return fail(Status::InvalidArgument, "%s: radius must be > 0, got %g", k, s.radius);
      if (s.kind != ShapeKind::Sphere) {
        if (!std::isfinite(s.halfHeight) || s.halfHeight < 0.0 ||
            (s.kind == ShapeKind::Cylinder && !(s.halfHeight > 0.0)))
          return fail(Status::InvalidArgument, "%s: halfHeight must be %s 0, got %g", k,
                      s.kind == ShapeKind::Cylinder ? ">" : ">=", s.halfHeight);
      }
      break;
    case ShapeKind::Box:
      if (!finite3(s.halfExtents) || !(s.halfExtents.minCoeff() > 0.0))
        return fail(Status::InvalidArgument, "box: halfExtents must be > 0, got (%g, %g, %g)",
                    s.halfExtents.x(), s.halfExtents.y(), s.halfExtents.z());
      break;
    case ShapeKind::Plane:
      if (!finite3(s.planeNormal) || !(s.planeNormal.norm() > 0.0) ||
          !std::isfinite(s.planeOffset))
        return fail(Status::InvalidArgument,
                    "plane: planeNormal must be finite and non-zero, planeOffset finite "
                    "(normal (%g, %g, %g), offset %g)",
                    s.planeNormal.x(), s.planeNormal.y(), s.planeNormal.z(), s.planeOffset);
      break;
    case ShapeKind::ConvexHull:
      for (size_t i = 0; i < s.hullPoints.size(); ++i)
        if (!finite3(s.hullPoints[i]))
          return fail(Status::InvalidArgument, "convexHull: hullPoints[%zu] is not finite", i);
      break;
    case ShapeKind::TriangleMesh: {
      const int nv = static_cast<int>(s.meshVertices.size());
      if (s.meshTriangles.size() < 4)
        return fail(Status::InvalidArgument,
                    "triangleMesh: a closed mesh needs >= 4 meshTriangles, got %zu",
                    s.meshTriangles.size());
      for (int i = 0; i < nv; ++i)
        if (!finite3(s.meshVertices[i]))
          return fail(Status::InvalidArgument, "triangleMesh: meshVertices[%d] is not finite", i);
      for (size_t t = 0; t < s.meshTriangles.size(); ++t) {
        const Eigen::Vector3i& tri = s.meshTriangles[t];
        for (int c = 0; c < 3; ++c) {
          if (tri[c] < 0 || tri[c] >= nv)
            return fail(Status::InvalidArgument,
                        "triangleMesh: meshTriangles[%zu][%d] = %d out of range [0, %d)", t, c,
                        tri[c], nv);
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
          return fail(Status::InvalidArgument, "triangleMesh: meshTriangles[%zu] repeats a vertex", t);
      }
      // Inside and outside are decided by the surface: it must be closed (geometry/closed_surface.h).
      VP_TRY(checkClosedSurface(s.meshVertices, s.meshTriangles, "triangleMesh"));
      break;
    }
  }
  return Status::Ok;
}

void updateWorld(PreparedCollider* c) {
  const ColliderShape& s = c->shape;
  const Eigen::Matrix3d& R = c->rotation;
  const Eigen::Vector3d& t = c->translation;
  Aabb b;
  switch (s.kind) {
    case ShapeKind::Sphere:
      b.lo = t.array() - s.radius;
      b.hi = t.array() + s.radius;
      break;
    case ShapeKind::Box: {
      const Eigen::Vector3d ext = R.cwiseAbs() * s.halfExtents;
      b.lo = t - ext;
      b.hi = t + ext;
      break;
    }
    case ShapeKind::Capsule:
    case ShapeKind::Cylinder: {
      const Eigen::Vector3d axis = R.col(1);
      Eigen::Vector3d ext;
      for (int i = 0; i < 3; ++i) {
        const double ai = std::min(1.0, std::fabs(axis[i]));
        ext[i] = ai * s.halfHeight +
                 s.radius * (s.kind == ShapeKind::Capsule ? 1.0 : std::sqrt(1.0 - ai * ai));
      }
      b.lo = t - ext;
      b.hi = t + ext;
      break;
    }
    case ShapeKind::Plane: {
      b.lo = Eigen::Vector3d::Constant(-kHuge);
      b.hi = Eigen::Vector3d::Constant(kHuge);
      break;
    }
    case ShapeKind::ConvexHull: {
      b.lo = Eigen::Vector3d::Constant(kHuge);
      b.hi = Eigen::Vector3d::Constant(-kHuge);
      for (const auto& p : s.hullPoints) {
        const Eigen::Vector3d w = R * p + t;
        b.lo = b.lo.cwiseMin(w);
        b.hi = b.hi.cwiseMax(w);
      }
      break;
    }
    case ShapeKind::TriangleMesh: {
      c->worldVertices.resize(s.meshVertices.size());
      b.lo = Eigen::Vector3d::Constant(kHuge);
      b.hi = Eigen::Vector3d::Constant(-kHuge);
      for (size_t i = 0; i < s.meshVertices.size(); ++i) {
        c->worldVertices[i] = R * s.meshVertices[i] + t;
        b.lo = b.lo.cwiseMin(c->worldVertices[i]);
        b.hi = b.hi.cwiseMax(c->worldVertices[i]);
      }
      detail::buildTriangleBvh(c->worldVertices, c->triangles, &c->bvh);
      break;
    }
  }
  c->worldPlanes.resize(c->localPlanes.size());
  for (size_t i = 0; i < c->localPlanes.size(); ++i) {
    const Eigen::Vector3d n = R * c->localPlanes[i].head<3>();
    const double d = c->localPlanes[i].w() + n.dot(t);
    c->worldPlanes[i] = Eigen::Vector4d(n.x(), n.y(), n.z(), d);
  }
  if (s.kind == ShapeKind::Plane) {
    // An axis-aligned half-space is bounded on one side along that axis.
    const Eigen::Vector4d& p = c->worldPlanes[0];
    for (int i = 0; i < 3; ++i) {
      if (p[i] == 1.0) b.hi[i] = p.w();
      if (p[i] == -1.0) b.lo[i] = -p.w();
    }
  }
  c->bounds = b;
  c->boundCentre = 0.5 * (b.lo + b.hi);
  c->boundRadius = s.kind == ShapeKind::Plane ? std::numeric_limits<double>::infinity()
                                              : 0.5 * (b.hi - b.lo).norm();
}

}  // namespace

Aabb faceBounds(const AxisFace& face) {
  Aabb b;
  b.lo = face.centre.array() - 0.5 * face.h;
  b.hi = face.centre.array() + 0.5 * face.h;
  b.lo[face.axis] = b.hi[face.axis] = face.centre[face.axis];
  return b;
}

Status prepareCollider(const ColliderShape& shape, PreparedCollider* out) {
  if (out == nullptr) return fail(Status::InvalidArgument, "prepareCollider: out is null");
  VP_TRY(validateShape(shape));
  PreparedCollider c;
  c.shape = shape;
  c.shape.rotation.normalize();
  c.rotation = c.shape.rotation.toRotationMatrix();
  c.translation = shape.translation;
  switch (shape.kind) {
    case ShapeKind::Box:
      for (int i = 0; i < 3; ++i) {
        Eigen::Vector4d p = Eigen::Vector4d::Zero();
        p[i] = 1.0;
        p.w() = shape.halfExtents[i];
        c.localPlanes.push_back(p);
        p[i] = -1.0;
        c.localPlanes.push_back(p);
      }
      break;
    case ShapeKind::Plane: {
      const double len = shape.planeNormal.norm();
      const Eigen::Vector3d n = shape.planeNormal / len;
      c.localPlanes.emplace_back(n.x(), n.y(), n.z(), shape.planeOffset / len);
      break;
    }
    case ShapeKind::ConvexHull:
      VP_TRY(detail::convexHullPlanes(shape.hullPoints, &c.localPlanes));
      break;
    case ShapeKind::TriangleMesh: {
      c.triangles = shape.meshTriangles;
      double vol6 = 0.0;
      for (const auto& t : c.triangles)
        vol6 += shape.meshVertices[t[0]].dot(shape.meshVertices[t[1]].cross(shape.meshVertices[t[2]]));
      if (vol6 == 0.0)
        return fail(Status::InvalidArgument, "triangleMesh: encloses zero volume");
      if (vol6 < 0.0)
        for (auto& t : c.triangles) std::swap(t[1], t[2]);  // inward-oriented: flip
      break;
    }
    default:
      break;
  }
  updateWorld(&c);
  *out = std::move(c);
  return Status::Ok;
}

Status setColliderPose(PreparedCollider* c, const Eigen::Quaterniond& rotation,
                       const Eigen::Vector3d& translation) {
  if (c == nullptr) return fail(Status::InvalidArgument, "setColliderPose: collider is null");
  if (!rotation.coeffs().allFinite() || !(rotation.norm() > 1e-12) || !translation.allFinite())
    return fail(Status::InvalidArgument, "setColliderPose: rotation/translation not finite or zero");
  c->shape.rotation = rotation.normalized();
  c->shape.translation = translation;
  c->rotation = c->shape.rotation.toRotationMatrix();
  c->translation = translation;
  updateWorld(c);
  return Status::Ok;
}

void restoreColliderPose(PreparedCollider* c, const Eigen::Quaterniond& unitRotation,
                         const Eigen::Vector3d& translation) {
  c->shape.rotation = unitRotation;
  c->shape.translation = translation;
  c->rotation = c->shape.rotation.toRotationMatrix();
  c->translation = translation;
  updateWorld(c);
}

Status prepareDeformingSurface(const Array<Eigen::Vector3d>& vertices, const Array<Eigen::Vector3i>& triangles,
                               PreparedCollider* out) {
  if (out == nullptr) return fail(Status::InvalidArgument, "prepareDeformingSurface: out is null");
  ColliderShape shape;
  shape.kind = ShapeKind::TriangleMesh;
  shape.meshVertices = vertices;
  shape.meshTriangles = triangles;
  PreparedCollider c;
  VP_TRY(prepareCollider(shape, &c));
  c.vertexVelocities.assign(vertices.size(), Eigen::Vector3d::Zero());
  *out = std::move(c);
  return Status::Ok;
}

void setDeformingSurface(PreparedCollider* c, const Array<Eigen::Vector3d>& vertices,
                         const Array<Eigen::Vector3d>& velocities) {
  c->shape.meshVertices = vertices;
  c->vertexVelocities = velocities;
  c->meanVertexVelocity = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : velocities) c->meanVertexVelocity += v;
  if (!velocities.empty()) c->meanVertexVelocity /= static_cast<double>(velocities.size());
  ++c->surfaceMoves;
  updateWorld(c);
}

}  // namespace vp

// Dispatch of face coverage per shape kind, the conservative reject test and the signed
// distance bounds shared by the reject test and the union path.
#include "collide/face_coverage_detail.h"
#include "geometry/closest_point_on_triangle.h"

#include <limits>

namespace vp {

double signedDistanceBound(const PreparedCollider& c, const Eigen::Vector3d& x) {
  const ColliderShape& s = c.shape;
  switch (s.kind) {
    case ShapeKind::Sphere:
      return (x - c.translation).norm() - s.radius;
    case ShapeKind::Plane:
    case ShapeKind::ConvexHull: {
      double d = -std::numeric_limits<double>::infinity();
      for (const auto& p : c.worldPlanes) d = std::max(d, p.head<3>().dot(x) - p.w());
      return d;
    }
    case ShapeKind::Box: {
      const Eigen::Vector3d q =
          (c.rotation.transpose() * (x - c.translation)).cwiseAbs() - s.halfExtents;
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    case ShapeKind::Capsule: {
      Eigen::Vector3d p = c.rotation.transpose() * (x - c.translation);
      p.y() -= std::min(s.halfHeight, std::max(-s.halfHeight, p.y()));
      return p.norm() - s.radius;
    }
    case ShapeKind::Cylinder: {
      const Eigen::Vector3d p = c.rotation.transpose() * (x - c.translation);
      const double qx = std::hypot(p.x(), p.z()) - s.radius;
      const double qy = std::fabs(p.y()) - s.halfHeight;
      return std::min(std::max(qx, qy), 0.0) +
             std::hypot(std::max(qx, 0.0), std::max(qy, 0.0));
    }
    case ShapeKind::TriangleMesh: {
      const double d = detail::meshUnsignedDistance(c, x);
      return detail::meshContains(c, x) ? -d : d;
    }
  }
  return std::numeric_limits<double>::infinity();
}

int classifyFace(const PreparedCollider& c, const AxisFace& face) {
  if (!c.bounds.overlaps(faceBounds(face))) return -1;
  const double halfDiag = 0.70710678118654757 * face.h;
  if (c.shape.kind != ShapeKind::Plane &&
      (face.centre - c.boundCentre).norm() >= c.boundRadius + halfDiag)
    return -1;
  if (c.shape.kind == ShapeKind::TriangleMesh) return 0;  // the exact path is cheaper
  const double d = signedDistanceBound(c, face.centre);
  if (d >= halfDiag) return -1;
  if (d <= -halfDiag) return 1;
  return 0;
}

double coveredFraction(const PreparedCollider& c, const AxisFace& face) {
  const int cls = classifyFace(c, face);
  if (cls != 0) return cls > 0 ? 1.0 : 0.0;
  const detail::FaceFrame fr = detail::makeFrame(face);
  double area = 0.0;
  switch (c.shape.kind) {
    case ShapeKind::Sphere: area = detail::coveredAreaSphere(c, fr); break;
    case ShapeKind::Box:
    case ShapeKind::Plane:
    case ShapeKind::ConvexHull:
      area = detail::coveredAreaHalfSpaces(c.worldPlanes.data(),
                                           static_cast<int>(c.worldPlanes.size()), fr);
      break;
    case ShapeKind::Capsule:
    case ShapeKind::Cylinder: area = detail::coveredAreaCapsuleOrCylinder(c, fr); break;
    case ShapeKind::TriangleMesh: area = detail::coveredAreaMesh(c, fr); break;
  }
  return std::min(1.0, std::max(0.0, area / fr.area()));
}

double coveredFractionAndCentroid(const PreparedCollider& c, const AxisFace& face, Eigen::Vector3d* centroid) {
  *centroid = face.centre;
  if (c.shape.kind != ShapeKind::TriangleMesh || classifyFace(c, face) < 0) return coveredFraction(c, face);
  const detail::FaceFrame fr = detail::makeFrame(face);
  const detail::CoveredMoments m = detail::coveredMomentsMesh(c, fr);
  if (m.area > 0.0) {
    (*centroid)[fr.a1] = m.u / m.area;
    (*centroid)[fr.a2] = m.v / m.area;
  }
  return std::min(1.0, std::max(0.0, m.area / fr.area()));
}

double coveredFractionAndTraceVelocity(const PreparedCollider& c, const AxisFace& face, Eigen::Vector3d* velocity,
                                       bool* traced) {
  *traced = false;
  const int cls = classifyFace(c, face);
  if (cls != 0) return cls > 0 ? 1.0 : 0.0;
  const detail::FaceFrame fr = detail::makeFrame(face);
  detail::SurfaceTrace trace;
  const double area = detail::coveredAreaAndTraceMesh(c, fr, &trace);
  if (trace.length > 0.0) {
    *velocity = trace.velocity / trace.length;
    *traced = true;
  }
  return std::min(1.0, std::max(0.0, area / fr.area()));
}

double coveredFraction(const ColliderShape& shape, const AxisFace& face) {
  PreparedCollider c;
  if (!ok(prepareCollider(shape, &c))) return std::numeric_limits<double>::quiet_NaN();
  return coveredFraction(c, face);
}

bool solidContains(const PreparedCollider& c, const Eigen::Vector3d& x) {
  if (c.shape.kind != ShapeKind::TriangleMesh) return signedDistanceBound(c, x) < 0.0;
  const Aabb& b = c.bounds;
  if ((x.array() < b.lo.array()).any() || (x.array() > b.hi.array()).any()) return false;
  return detail::meshContains(c, x);
}

Eigen::Vector3d solidVelocityAt(const PreparedCollider& c, const Eigen::Vector3d& x) {
  if (c.vertexVelocities.empty())
    return c.shape.linearVelocity + c.shape.angularVelocity.cross(x - c.translation);
  int triangle = -1;
  Eigen::Vector3d q;
  detail::meshClosestPoint(c, x, &triangle, &q);
  if (triangle < 0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3i& t = c.triangles[triangle];
  const Eigen::Vector3d w = barycentricWeights(q, c.worldVertices[t[0]], c.worldVertices[t[1]], c.worldVertices[t[2]]);
  return w[0] * c.vertexVelocities[t[0]] + w[1] * c.vertexVelocities[t[1]] + w[2] * c.vertexVelocities[t[2]];
}

double solidSpeedBound(const PreparedCollider& c) {
  if (c.vertexVelocities.empty()) {
    // A plane's bound radius is infinite: without spin it adds nothing (0 * inf is NaN, which
    // the sub-step rule's max would drop with the plane's own speed).
    const double spin = c.shape.angularVelocity.norm();
    return c.shape.linearVelocity.norm() + (spin > 0.0 ? spin * c.boundRadius : 0.0);
  }
  double fastest = 0.0;
  for (const Eigen::Vector3d& v : c.vertexVelocities) fastest = std::max(fastest, v.squaredNorm());
  return std::sqrt(fastest);
}

}  // namespace vp

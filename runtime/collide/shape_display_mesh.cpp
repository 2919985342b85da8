#include "collide/shape_display_mesh.h"

#include <LinearMath/btConvexHullComputer.h>

#include <cmath>

namespace vp {
namespace {

constexpr int kSegments = 24;  // around the axis of round shapes
constexpr int kRings = 12;     // pole to pole of a sphere (even: capsules split at the equator)

struct Builder {
  ShapeDisplayMesh mesh;
  int32_t add(const Vec3& p, const Vec3& n) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n.normalized());
    return static_cast<int32_t>(mesh.positions.size()) - 1;
  }
  void tri(int32_t a, int32_t b, int32_t c) { mesh.triangles.push_back({a, b, c}); }
  // Flat polygon (convex, in order either way round) with one normal: a fan.
  void polygon(const Array<Vec3>& corners, const Vec3& normal) {
    Array<int32_t> ids;
    for (const Vec3& c : corners) ids.push_back(add(c, normal));
    for (size_t i = 1; i + 1 < ids.size(); ++i) tri(ids[0], ids[i], ids[i + 1]);
  }
};

// Rings of a sphere of `radius`, the upper half lifted by `lift` and the lower half lowered by
// it: a sphere for lift 0, a capsule otherwise (the equator ring appears once per half).
void addRoundedBody(Builder& b, double radius, double lift) {
  const double pi = 3.14159265358979323846;
  std::vector<std::pair<double, double>> rings;  // (polar angle, y offset)
  for (int i = 0; i <= kRings / 2; ++i) rings.emplace_back(pi * i / kRings, lift);
  for (int i = kRings / 2 + (lift == 0.0 ? 1 : 0); i <= kRings; ++i) rings.emplace_back(pi * i / kRings, -lift);
  Array<int32_t> first;
  for (const auto& [theta, y] : rings) {
    first.push_back(static_cast<int32_t>(b.mesh.positions.size()));
    for (int j = 0; j < kSegments; ++j) {
      const double phi = 2.0 * pi * j / kSegments;
      const Vec3 dir(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      b.add(radius * dir + Vec3(0, y, 0), dir);
    }
  }
  for (size_t r = 0; r + 1 < rings.size(); ++r)
    for (int j = 0; j < kSegments; ++j) {
      const int32_t a = first[r] + j, c = first[r] + (j + 1) % kSegments;
      const int32_t d = first[r + 1] + j, e = first[r + 1] + (j + 1) % kSegments;
      // At the poles one edge of the quad has length zero: keep only its real triangle.
      if (r > 0) b.tri(a, c, d);
      if (r + 2 < rings.size()) b.tri(c, e, d);
    }
}

void addCylinder(Builder& b, double radius, double halfHeight) {
  const double pi = 3.14159265358979323846;
  const int32_t base = static_cast<int32_t>(b.mesh.positions.size());
  Array<Vec3> top, bottom;
  for (int j = 0; j < kSegments; ++j) {
    const double phi = 2.0 * pi * j / kSegments;
    const Vec3 radial(std::cos(phi), 0, std::sin(phi));
    b.add(radius * radial + Vec3(0, halfHeight, 0), radial);
    b.add(radius * radial - Vec3(0, halfHeight, 0), radial);
    top.push_back(radius * radial + Vec3(0, halfHeight, 0));
    bottom.push_back(radius * radial - Vec3(0, halfHeight, 0));
  }
  for (int j = 0; j < kSegments; ++j) {
    const int32_t a = base + 2 * j, c = base + 2 * ((j + 1) % kSegments);
    b.tri(a, c, a + 1);
    b.tri(c, c + 1, a + 1);
  }
  b.polygon(top, Vec3(0, 1, 0));
  b.polygon(bottom, Vec3(0, -1, 0));
}

void addBox(Builder& b, const Vec3& he) {
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      Vec3 n = Vec3::Zero();
      n[axis] = s;
      Array<Vec3> corners;
      for (auto [cu, cv] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        Vec3 p = Vec3::Zero();
        p[axis] = s * he[axis];
        p[u] = cu * he[u];
        p[v] = cv * he[v];
        corners.push_back(p);
      }
      b.polygon(corners, n);
    }
}

void addPlane(Builder& b, const Vec3& normal, double offset) {
  const Vec3 n = normal.normalized();
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 t = n.cross(helper).normalized(), u = n.cross(t);
  const Vec3 c = n * offset;
  const double h = kPlaneDisplayHalfSize;
  b.polygon({c - h * t - h * u, c + h * t - h * u, c + h * t + h * u, c - h * t + h * u}, n);
}

void addConvexHull(Builder& b, const Array<Vec3>& points) {
  Array<double> xyz;
  for (const Vec3& p : points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  btConvexHullComputer hull;
  hull.compute(xyz.data(), 3 * static_cast<int>(sizeof(double)), static_cast<int>(points.size()), 0, 0);
  for (int f = 0; f < hull.faces.size(); ++f) {
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    const btConvexHullComputer::Edge* e = first;
    Array<Vec3> corners;
    do {
      const btVector3& v = hull.vertices[e->getSourceVertex()];
      corners.emplace_back(v.x(), v.y(), v.z());
      e = e->getNextEdgeOfFace();
    } while (e != first);
    if (corners.size() < 3) continue;
    Vec3 n = Vec3::Zero();  // Newell's normal: robust for any planar polygon
    for (size_t i = 0; i < corners.size(); ++i) n += corners[i].cross(corners[(i + 1) % corners.size()]);
    if (n.norm() > 0) b.polygon(corners, n);
  }
}

void addTriangleMesh(Builder& b, const ShapeDesc& shape) {
  // Flat shading with the mesh's own winding: a mesh may be open and carry no inside.
  for (const auto& t : shape.triangles) {
    const Vec3 &p = shape.points[t[0]], &q = shape.points[t[1]], &r = shape.points[t[2]];
    const Vec3 n = (q - p).cross(r - p);
    if (n.norm() == 0) continue;
    b.tri(b.add(p, n), b.add(q, n), b.add(r, n));
  }
}

// Builders above do not track winding; make every triangle counter-clockwise seen from the
// side its vertex normals point to.
void orientByNormals(ShapeDisplayMesh& m) {
  for (auto& t : m.triangles) {
    const Vec3 face = (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
    if (face.dot(m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]]) < 0) std::swap(t[1], t[2]);
  }
}

}  // namespace

ShapeDisplayMesh buildShapeDisplayMesh(const ShapeDesc& shape) {
  Builder b;
  switch (shape.type) {
    case ShapeType::Sphere: addRoundedBody(b, shape.radius, 0.0); break;
    case ShapeType::Capsule: addRoundedBody(b, shape.radius, shape.halfHeight); break;
    case ShapeType::Cylinder: addCylinder(b, shape.radius, shape.halfHeight); break;
    case ShapeType::Box: addBox(b, shape.halfExtents); break;
    case ShapeType::Plane: addPlane(b, shape.normal, shape.offset); break;
    case ShapeType::ConvexHull: addConvexHull(b, shape.points); break;
    case ShapeType::TriangleMesh: addTriangleMesh(b, shape); break;
  }
  orientByNormals(b.mesh);
  return std::move(b.mesh);
}

}  // namespace vp

#include "query/triangle_queries.h"

#include <algorithm>
#include <cmath>

namespace vp {

bool rayHitsTriangle(const Vec3& origin, const Vec3& direction, double maxDistance, const Vec3& a, const Vec3& b,
                     const Vec3& c, TriangleRayHit* hit) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = direction.cross(e2);
  const double det = e1.dot(p);
  // Relative to the edge lengths: the ray lies (numerically) in the triangle's plane.
  if (std::abs(det) <= 1e-14 * e1.norm() * e2.norm()) return false;
  const double inv = 1.0 / det;
  const Vec3 s = origin - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 q = s.cross(e1);
  const double v = direction.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = e2.dot(q) * inv;
  if (t < 0.0 || t > maxDistance) return false;
  hit->distance = t;
  hit->barycentric = Vec3(1.0 - u - v, u, v);
  return true;
}

namespace {

// Whether the projections of the triangle (vertices v relative to the box centre) and of the
// box onto `axis` are disjoint.
bool separates(const Vec3& axis, const Vec3 v[3], const Vec3& halfExtents, const Mat3& axes) {
  if (axis.squaredNorm() < 1e-24) return false;  // parallel edges: covered by the other axes
  const double p0 = axis.dot(v[0]), p1 = axis.dot(v[1]), p2 = axis.dot(v[2]);
  double r = 0.0;
  for (int k = 0; k < 3; ++k) r += halfExtents[k] * std::abs(axis.dot(axes.col(k)));
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

}  // namespace

bool triangleOverlapsBox(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& centre, const Vec3& halfExtents,
                         const Mat3& axes) {
  const Vec3 v[3] = {a - centre, b - centre, c - centre};
  for (int k = 0; k < 3; ++k)
    if (separates(axes.col(k), v, halfExtents, axes)) return false;
  const Vec3 edges[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  if (separates(edges[0].cross(edges[1]), v, halfExtents, axes)) return false;
  for (int k = 0; k < 3; ++k)
    for (const Vec3& e : edges)
      if (separates(axes.col(k).cross(e), v, halfExtents, axes)) return false;
  return true;
}

}  // namespace vp

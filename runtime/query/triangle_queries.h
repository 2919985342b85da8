// Exact tests of one triangle against a ray and a box (against a point:
// geometry/closest_point_on_triangle.h): the pieces of the
// deformable-surface queries (query/world_query.h). Triangles are (a, b, c), counter-clockwise
// seen from outside; rays have a unit direction.
#pragma once

#include "core/math_types.h"

namespace vp {

struct TriangleRayHit {
  double distance = 0.0;   // along the ray
  Vec3 barycentric;        // weights of a, b, c at the hit
};

// Möller–Trumbore: hits from either side within [0, maxDistance]; false for a ray in the
// triangle's plane (grazing hits are left to the neighbouring triangles).
bool rayHitsTriangle(const Vec3& origin, const Vec3& direction, double maxDistance, const Vec3& a, const Vec3& b,
                     const Vec3& c, TriangleRayHit* hit);

// Whether the triangle and the box (centre, half extents along the box's axes, given as the
// columns of `axes`) share a point: the separating-axis test over the box's 3 face normals,
// the triangle's normal and the 9 edge cross products (Akenine-Möller 2001).
bool triangleOverlapsBox(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& centre, const Vec3& halfExtents,
                         const Mat3& axes);

}  // namespace vp

// Internal helpers shared by the face_coverage_*.cpp files (not part of the fluid API).
#pragma once

#include "core/allocator.h"
#include "collide/face_coverage.h"

#include <algorithm>
#include <cmath>

namespace vp {
namespace detail {

// The face in its in-plane frame: u = x[a1], v = x[a2], plane x[a] = c0.
struct FaceFrame {
  int a, a1, a2;
  double c0, u0, u1, v0, v1;
  double area() const { return (u1 - u0) * (v1 - v0); }
};

inline FaceFrame makeFrame(const AxisFace& f) {
  FaceFrame fr;
  fr.a = f.axis;
  fr.a1 = (f.axis + 1) % 3;
  fr.a2 = (f.axis + 2) % 3;
  fr.c0 = f.centre[fr.a];
  const double r = 0.5 * f.h;
  fr.u0 = f.centre[fr.a1] - r;
  fr.u1 = f.centre[fr.a1] + r;
  fr.v0 = f.centre[fr.a2] - r;
  fr.v1 = f.centre[fr.a2] + r;
  return fr;
}

// A convex polygon in fixed storage (no allocation), clipped in place.
template <int Capacity>
struct FixedPolygon {
  double x[Capacity];
  double y[Capacity];
  int n = 0;

  void setRect(double x0, double y0, double x1, double y1) {
    x[0] = x0; y[0] = y0;
    x[1] = x1; y[1] = y0;
    x[2] = x1; y[2] = y1;
    x[3] = x0; y[3] = y1;
    n = 4;
  }

  // Keeps the part with a*x + b*y <= c. Returns false when nothing is left.
  bool clip(double a, double b, double c) {
    if (n == 0) return false;
    double ox[Capacity], oy[Capacity];
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      const double si = a * x[i] + b * y[i] - c;
      const double sj = a * x[j] + b * y[j] - c;
      const bool inI = si <= 0.0, inJ = sj <= 0.0;
      if (inI) { ox[m] = x[i]; oy[m] = y[i]; ++m; }
      if (inI != inJ && m < Capacity) {
        const double t = si / (si - sj);
        ox[m] = x[i] + t * (x[j] - x[i]);
        oy[m] = y[i] + t * (y[j] - y[i]);
        ++m;
      }
      if (m >= Capacity) break;  // cannot happen for <= Capacity-4 clips of a rectangle
    }
    for (int i = 0; i < m; ++i) { x[i] = ox[i]; y[i] = oy[i]; }
    n = m;
    return n >= 3;
  }

  double area() const {
    double s = 0.0;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      s += x[i] * y[j] - x[j] * y[i];
    }
    return n >= 3 ? 0.5 * std::fabs(s) : 0.0;
  }
};

// Area of the disc (centre (cx,cy), radius r) inside the rectangle [x0,x1]x[y0,y1]. Exact.
double discRectangleArea(double cx, double cy, double r, double x0, double y0, double x1,
                         double y1);

// Area of the disc (centre (cx,cy), radius r) inside the convex polygon (x[i], y[i]), i < n,
// either orientation. Exact: the sum over edges of the disc's part of the triangle (centre,
// edge), each a triangle or a circular sector piece by piece between the edge's crossings.
double discPolygonArea(double cx, double cy, double r, const double* x, const double* y, int n);

// Clips `poly` by a solid's half-spaces in the face plane (plane, box, convex hull);
// false when nothing is left. Each clip adds at most one vertex, so Capacity must exceed 4
// plus the number of half-spaces clipped by since setRect.
template <int Capacity>
bool clipByHalfSpaces(FixedPolygon<Capacity>& poly, const Eigen::Vector4d* planes, int count, const FaceFrame& fr) {
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector4d& p = planes[i];
    const double a = p[fr.a1], b = p[fr.a2], c = p.w() - p[fr.a] * fr.c0;
    if (a == 0.0 && b == 0.0) {  // parallel to the face: all or nothing
      if (c < 0.0) return false;
      continue;
    }
    if (!poly.clip(a, b, c)) return false;
  }
  return true;
}

// The disc a sphere cuts from the face plane; false when the plane misses the sphere.
bool sphereCrossSection(const PreparedCollider& c, const FaceFrame& fr, double* cu, double* cv, double* radius);

// Per-family kernels: covered AREA (not fraction) of the face square.
double coveredAreaHalfSpaces(const Eigen::Vector4d* planes, int count, const FaceFrame& fr);
double coveredAreaSphere(const PreparedCollider& c, const FaceFrame& fr);
double coveredAreaCapsuleOrCylinder(const PreparedCollider& c, const FaceFrame& fr);
double coveredAreaMesh(const PreparedCollider& c, const FaceFrame& fr);
// The covered part's area and first moments ∫u dA, ∫v dA in the face's (u, v) frame; the area
// is bitwise coveredAreaMesh's.
struct CoveredMoments {
  double area = 0.0, u = 0.0, v = 0.0;
};
CoveredMoments coveredMomentsMesh(const PreparedCollider& c, const FaceFrame& fr);
// A deforming surface's trace on the face: the length of the segments where it meets the face's
// rectangle, and the integral of its interpolated vertex velocity along them.
struct SurfaceTrace {
  double length = 0.0;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};
// The covered area as coveredAreaMesh gives it (bitwise) and the trace (c.vertexVelocities set).
double coveredAreaAndTraceMesh(const PreparedCollider& c, const FaceFrame& fr, SurfaceTrace* trace);

// Convex-hull half-spaces of a point set (local frame): unit n, d in w; n.x <= d inside.
Status convexHullPlanes(const Array<Eigen::Vector3d>& points,
                        Array<Eigen::Vector4d>* planes);

// BVH over triangles of `vertices`.
void buildTriangleBvh(const Array<Eigen::Vector3d>& vertices,
                      const Array<Eigen::Vector3i>& triangles, TriangleBvh* bvh);

// Calls visit(triangleId) for every triangle whose box overlaps [lo, hi]. No allocation.
template <class Visit>
void bvhQueryBox(const TriangleBvh& bvh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                 Visit&& visit) {
  if (bvh.nodes.empty()) return;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const TriangleBvh::Node& nd = bvh.nodes[stack[--top]];
    if ((nd.lo.array() > hi.array()).any() || (nd.hi.array() < lo.array()).any()) continue;
    if (nd.count > 0) {
      for (int i = 0; i < nd.count; ++i) visit(bvh.order[nd.first + i]);
    } else {
      stack[top++] = nd.left;
      stack[top++] = nd.right;
    }
  }
}

// Unsigned distance from x to the mesh (BVH nearest search).
double meshUnsignedDistance(const PreparedCollider& c, const Eigen::Vector3d& x);
// The mesh's point nearest to x: its triangle (index into c.triangles) and the point.
void meshClosestPoint(const PreparedCollider& c, const Eigen::Vector3d& x, int* triangle, Eigen::Vector3d* point);
// True when x is inside the closed mesh (ray parity along a fixed skew direction).
bool meshContains(const PreparedCollider& c, const Eigen::Vector3d& x);

}  // namespace detail
}  // namespace vp

// Half-space representation of the convex hull of a point set, computed once per hull shape.
//
// Why half-spaces: the covered part of a face is (face square) ∩ (hull ∩ face plane), and the
// hull ∩ face plane is the intersection of the half-planes its face planes cut out of the face
// plane. Clipping the square by those half-planes gives the exact area with no need to build
// and order the cross-section's vertices, and the only degenerate case (a hull face parallel
// to the face plane) is an all-or-nothing half-plane.
//
// Algorithm: incremental hull (O(n * faces)): start from a non-degenerate tetrahedron, add each
// point that lies more than eps outside some face by replacing the faces it sees with a fan to
// their horizon. Points within eps (1e-10 of the bounding diagonal) of the hull are ignored,
// so the hull is exact up to that distance; the result is checked to contain every input point
// within 1e-8 of the diagonal. Near-duplicate planes (coplanar triangles) are merged.
#include "collide/face_coverage_detail.h"

#include <algorithm>
#include <utility>

namespace vp {
namespace detail {
namespace {

struct HullFace {
  int v[3];
  Eigen::Vector3d n;  // unit outward normal
  double d;
  bool alive;
};

bool makeFace(const Array<Eigen::Vector3d>& p, int a, int b, int c, HullFace* f) {
  Eigen::Vector3d n = (p[b] - p[a]).cross(p[c] - p[a]);
  const double len = n.norm();
  if (!(len > 0.0)) return false;
  n /= len;
  f->v[0] = a; f->v[1] = b; f->v[2] = c;
  f->n = n;
  f->d = n.dot(p[a]);
  f->alive = true;
  return true;
}

}  // namespace

Status convexHullPlanes(const Array<Eigen::Vector3d>& p,
                        Array<Eigen::Vector4d>* planes) {
  const int n = static_cast<int>(p.size());
  if (n < 4) return fail(Status::InvalidArgument, "hullPoints: need at least 4 points, got %d", n);
  Eigen::Vector3d lo = p[0], hi = p[0];
  for (const auto& q : p) { lo = lo.cwiseMin(q); hi = hi.cwiseMax(q); }
  const double diag = (hi - lo).norm();
  if (!(diag > 0.0)) return fail(Status::InvalidArgument, "hullPoints: all points coincide");
  const double eps = 1e-10 * diag;

  // Initial tetrahedron.
  int i0 = 0;
  for (int i = 1; i < n; ++i) if (p[i].x() < p[i0].x()) i0 = i;
  int i1 = -1; double best = 0.0;
  for (int i = 0; i < n; ++i) { double d = (p[i] - p[i0]).norm(); if (d > best) { best = d; i1 = i; } }
  int i2 = -1; best = 0.0;
  const Eigen::Vector3d e01 = (p[i1] - p[i0]).normalized();
  for (int i = 0; i < n; ++i) {
    double d = (p[i] - p[i0]).cross(e01).norm();
    if (d > best) { best = d; i2 = i; }
  }
  if (i2 < 0 || best <= 1e-8 * diag)
    return fail(Status::InvalidArgument, "hullPoints: points are collinear (hull has no volume)");
  const Eigen::Vector3d n012 = (p[i1] - p[i0]).cross(p[i2] - p[i0]).normalized();
  int i3 = -1; best = 0.0;
  for (int i = 0; i < n; ++i) {
    double d = std::fabs(n012.dot(p[i] - p[i0]));
    if (d > best) { best = d; i3 = i; }
  }
  if (i3 < 0 || best <= 1e-8 * diag)
    return fail(Status::InvalidArgument, "hullPoints: points are coplanar (hull has no volume)");

  std::vector<HullFace> faces;
  const Eigen::Vector3d inner = 0.25 * (p[i0] + p[i1] + p[i2] + p[i3]);
  const int tet[4][3] = {{i0, i1, i2}, {i0, i3, i1}, {i1, i3, i2}, {i2, i3, i0}};
  for (const auto& t : tet) {
    HullFace f;
    makeFace(p, t[0], t[1], t[2], &f);
    if (f.n.dot(inner) - f.d > 0.0) {  // inward: flip
      makeFace(p, t[0], t[2], t[1], &f);
    }
    faces.push_back(f);
  }

  std::vector<std::pair<int, int>> edges;  // directed edges of visible faces
  std::vector<int> visible;
  for (int pi = 0; pi < n; ++pi) {
    if (pi == i0 || pi == i1 || pi == i2 || pi == i3) continue;
    visible.clear();
    for (int f = 0; f < static_cast<int>(faces.size()); ++f)
      if (faces[f].alive && faces[f].n.dot(p[pi]) - faces[f].d > eps) visible.push_back(f);
    if (visible.empty()) continue;
    edges.clear();
    for (int f : visible) {
      for (int k = 0; k < 3; ++k) edges.emplace_back(faces[f].v[k], faces[f].v[(k + 1) % 3]);
      faces[f].alive = false;
    }
    std::sort(edges.begin(), edges.end());
    for (const auto& e : edges) {
      if (std::binary_search(edges.begin(), edges.end(), std::make_pair(e.second, e.first)))
        continue;  // interior edge of the visible region
      HullFace f;
      if (makeFace(p, e.first, e.second, pi, &f)) faces.push_back(f);
    }
    if (faces.size() > 8 * static_cast<size_t>(n) + 64) {  // compact dead faces
      faces.erase(std::remove_if(faces.begin(), faces.end(),
                                 [](const HullFace& f) { return !f.alive; }),
                  faces.end());
    }
  }

  Array<Eigen::Vector4d> out;
  for (const auto& f : faces) {
    if (!f.alive) continue;
    bool dup = false;
    for (const auto& q : out) {
      if ((q.head<3>() - f.n).norm() < 1e-9 && std::fabs(q.w() - f.d) < 1e-9 * diag) {
        dup = true;
        break;
      }
    }
    if (!dup) out.emplace_back(f.n.x(), f.n.y(), f.n.z(), f.d);
  }
  for (int i = 0; i < n; ++i) {
    for (const auto& q : out) {
      if (q.head<3>().dot(p[i]) - q.w() > 1e-8 * diag)
        return fail(Status::Internal, "hullPoints: hull construction lost point %d", i);
    }
  }
  if (static_cast<int>(out.size()) > kMaxConvexPlanes)
    return fail(Status::Unsupported,
                "hullPoints: hull has %d faces, more than kMaxConvexPlanes=%d; simplify it",
                static_cast<int>(out.size()), kMaxConvexPlanes);
  *planes = std::move(out);
  return Status::Ok;
}

}  // namespace detail
}  // namespace vp

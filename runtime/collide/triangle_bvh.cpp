// Per-mesh acceleration for the triangle-mesh collider: a median-split AABB tree over the
// world-space triangles, with box queries (face cross-sections), nearest distance and a
// ray-parity inside test (used only by the union path's signed distance).
#include "collide/face_coverage_detail.h"
#include "geometry/closest_point_on_triangle.h"

#include <algorithm>
#include <limits>

namespace vp {
namespace detail {
namespace {

int buildNode(const Array<Eigen::Vector3d>& v, const Array<Eigen::Vector3i>& t,
              const Array<Eigen::Vector3d>& centroid, TriangleBvh* bvh, int first,
              int count, int depth) {
  const int id = static_cast<int>(bvh->nodes.size());
  bvh->nodes.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo, clo = lo, chi = hi;
  for (int i = first; i < first + count; ++i) {
    const Eigen::Vector3i& tri = t[bvh->order[i]];
    for (int k = 0; k < 3; ++k) { lo = lo.cwiseMin(v[tri[k]]); hi = hi.cwiseMax(v[tri[k]]); }
    clo = clo.cwiseMin(centroid[bvh->order[i]]);
    chi = chi.cwiseMax(centroid[bvh->order[i]]);
  }
  bvh->nodes[id].lo = lo;
  bvh->nodes[id].hi = hi;
  if (count <= 4 || depth >= 60) {  // depth cap keeps the query stack (64) safe
    bvh->nodes[id].first = first;
    bvh->nodes[id].count = count;
    return id;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int mid = first + count / 2;
  std::nth_element(bvh->order.begin() + first, bvh->order.begin() + mid,
                   bvh->order.begin() + first + count,
                   [&](int x, int y) { return centroid[x][axis] < centroid[y][axis]; });
  const int l = buildNode(v, t, centroid, bvh, first, mid - first, depth + 1);
  const int r = buildNode(v, t, centroid, bvh, mid, first + count - mid, depth + 1);
  bvh->nodes[id].left = l;
  bvh->nodes[id].right = r;
  return id;
}


double boxDistance2(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  return d.squaredNorm();
}

}  // namespace

void buildTriangleBvh(const Array<Eigen::Vector3d>& v,
                      const Array<Eigen::Vector3i>& t, TriangleBvh* bvh) {
  bvh->nodes.clear();
  bvh->order.resize(t.size());
  Array<Eigen::Vector3d> centroid(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    bvh->order[i] = static_cast<int>(i);
    centroid[i] = (v[t[i][0]] + v[t[i][1]] + v[t[i][2]]) / 3.0;
  }
  bvh->nodes.reserve(t.size() / 2 + 2);
  if (!t.empty()) buildNode(v, t, centroid, bvh, 0, static_cast<int>(t.size()), 0);
}

void meshClosestPoint(const PreparedCollider& c, const Eigen::Vector3d& x, int* triangle, Eigen::Vector3d* point) {
  const TriangleBvh& bvh = c.bvh;
  double best2 = std::numeric_limits<double>::infinity();
  int bestTriangle = -1;
  Eigen::Vector3d bestPoint = x;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const TriangleBvh::Node& nd = bvh.nodes[stack[--top]];
    if (boxDistance2(x, nd.lo, nd.hi) >= best2) continue;
    if (nd.count > 0) {
      for (int i = 0; i < nd.count; ++i) {
        const int id = bvh.order[nd.first + i];
        const Eigen::Vector3i& t = c.triangles[id];
        const Eigen::Vector3d q = closestPointOnTriangle(x, c.worldVertices[t[0]],
                                                    c.worldVertices[t[1]], c.worldVertices[t[2]]);
        const double d2 = (q - x).squaredNorm();
        if (d2 < best2) best2 = d2, bestTriangle = id, bestPoint = q;
      }
    } else {
      // Visit the nearer child first (pushed last).
      const TriangleBvh::Node& l = bvh.nodes[nd.left];
      const TriangleBvh::Node& r = bvh.nodes[nd.right];
      const bool leftNear = boxDistance2(x, l.lo, l.hi) <= boxDistance2(x, r.lo, r.hi);
      stack[top++] = leftNear ? nd.right : nd.left;
      stack[top++] = leftNear ? nd.left : nd.right;
    }
  }
  *triangle = bestTriangle;
  *point = bestPoint;
}

double meshUnsignedDistance(const PreparedCollider& c, const Eigen::Vector3d& x) {
  int triangle = -1;
  Eigen::Vector3d q;
  meshClosestPoint(c, x, &triangle, &q);
  return triangle < 0 ? std::numeric_limits<double>::infinity() : (q - x).norm();
}

bool meshContains(const PreparedCollider& c, const Eigen::Vector3d& x) {
  // A skew direction makes rays through edges/vertices of grid-aligned meshes unlikely.
  const Eigen::Vector3d dir = Eigen::Vector3d(0.5773, 0.6411, 0.5063).normalized();
  const Eigen::Vector3d inv = dir.cwiseInverse();
  const TriangleBvh& bvh = c.bvh;
  int crossings = 0;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const TriangleBvh::Node& nd = bvh.nodes[stack[--top]];
    const Eigen::Vector3d t0 = (nd.lo - x).cwiseProduct(inv), t1 = (nd.hi - x).cwiseProduct(inv);
    const double tmin = t0.cwiseMin(t1).maxCoeff(), tmax = t0.cwiseMax(t1).minCoeff();
    if (tmax < std::max(tmin, 0.0)) continue;
    if (nd.count > 0) {
      for (int i = 0; i < nd.count; ++i) {
        const Eigen::Vector3i& t = c.triangles[bvh.order[nd.first + i]];
        const Eigen::Vector3d& a = c.worldVertices[t[0]];
        const Eigen::Vector3d e1 = c.worldVertices[t[1]] - a, e2 = c.worldVertices[t[2]] - a;
        const Eigen::Vector3d pv = dir.cross(e2);
        const double det = e1.dot(pv);
        if (det == 0.0) continue;
        const Eigen::Vector3d s = x - a;
        const double u = s.dot(pv) / det;
        if (u < 0.0 || u > 1.0) continue;
        const Eigen::Vector3d qv = s.cross(e1);
        const double w = dir.dot(qv) / det;
        if (w < 0.0 || u + w > 1.0) continue;
        if (e2.dot(qv) / det > 0.0) ++crossings;
      }
    } else {
      stack[top++] = nd.left;
      stack[top++] = nd.right;
    }
  }
  return (crossings & 1) != 0;
}

}  // namespace detail
}  // namespace vp

// Lattice node signs against a closed mesh by crossings along lattice lines (see
// mesh_lattice_signs.h).
#include "collide/mesh_lattice_signs.h"

#include <algorithm>
#include <cmath>

#include "collide/face_coverage_detail.h"

namespace vp {
namespace {

constexpr int kNodes = 8;
// In cell sizes: a line nearer than this to a triangle's edge, or a crossing nearer to a node,
// does not decide (rounding could put it on either side).
constexpr double kTolerance = 1e-9;
// More triangles near one cell than this fit no fixed buffer: the crossings do not decide.
constexpr int kMaxTriangles = 512;

// The node's position, by the expression the split cut-cell pass uses (bitwise the same).
Eigen::Vector3d nodeAt(const Eigen::Vector3d& origin, double h, const Eigen::Vector3d& cell, const int (&n)[3]) {
  return origin + h * (cell + Eigen::Vector3d(n[0], n[1], n[2]) / (kNodes - 1));
}

// Coordinates along `axis` where the line through p along `axis` crosses the triangles `ids`,
// into at[0 .. *found); false when a crossing is too near a triangle's edge to decide.
bool lineCrossings(const PreparedCollider& mesh, const int* ids, int count, int axis, const Eigen::Vector3d& p,
                   double tol, double* at, int* found) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const double pu = p[u], pv = p[v];
  int n = 0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3i& t = mesh.triangles[ids[k]];
    const Eigen::Vector3d& a = mesh.worldVertices[t[0]];
    const Eigen::Vector3d& b = mesh.worldVertices[t[1]];
    const Eigen::Vector3d& c = mesh.worldVertices[t[2]];
    if (std::max({a[u], b[u], c[u]}) < pu - tol || std::min({a[u], b[u], c[u]}) > pu + tol ||
        std::max({a[v], b[v], c[v]}) < pv - tol || std::min({a[v], b[v], c[v]}) > pv + tol)
      continue;
    // Twice the signed area of (edge, p) in the projection along the axis: the edge's length
    // times p's signed distance from it.
    auto side = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& y, double* length) {
      const double du = y[u] - x[u], dv = y[v] - x[v];
      *length = std::hypot(du, dv);
      return du * (pv - x[v]) - dv * (pu - x[u]);
    };
    double la, lb, lc;
    const double ea = side(b, c, &la), eb = side(c, a, &lb), ec = side(a, b, &lc);
    const double area = (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
    // A triangle seen edge-on (the line nearly in its plane) within reach of p: no decision.
    if (!(std::abs(area) > tol * std::max({la, lb, lc}))) return false;
    const double s = area > 0.0 ? 1.0 : -1.0;
    if (s * ea < -tol * la || s * eb < -tol * lb || s * ec < -tol * lc) continue;  // clearly outside
    if (!(s * ea > tol * la && s * eb > tol * lb && s * ec > tol * lc)) return false;
    at[n++] = (ea * a[axis] + eb * b[axis] + ec * c[axis]) / area;
  }
  *found = n;
  return true;
}

}  // namespace

bool latticeNodesOutsideMesh(const PreparedCollider& mesh, const Eigen::Vector3d& origin, double h,
                             const Eigen::Vector3d& cell, std::array<uint64_t, 8>* outside) {
  const double tol = kTolerance * h;
  const int first[3] = {0, 0, 0}, last[3] = {kNodes - 1, kNodes - 1, kNodes - 1};
  const Eigen::Vector3d lo = nodeAt(origin, h, cell, first), hi = nodeAt(origin, h, cell, last);
  int ids[kMaxTriangles];
  int count = 0;
  bool overflow = false;
  const Eigen::Vector3d queryLo = lo.array() - tol, queryHi = hi.array() + tol;
  detail::bvhQueryBox(mesh.bvh, queryLo, queryHi, [&](int t) {
    if (count < kMaxTriangles) ids[count++] = t;
    else overflow = true;
  });
  if (overflow) return false;
  const bool startInside = detail::meshContains(mesh, lo);
  if (count == 0) {  // no surface in the cell: every node on the start node's side
    outside->fill(startInside ? 0 : ~uint64_t(0));
    return true;
  }
  bool inside[kNodes][kNodes][kNodes];
  double at[kMaxTriangles];
  // The signs along the line from node `n` (sign known) along `axis`.
  auto walk = [&](int axis, const int (&n)[3]) {
    int found = 0;
    if (!lineCrossings(mesh, ids, count, axis, nodeAt(origin, h, cell, n), tol, at, &found)) return false;
    double x[kNodes];
    for (int k = 0; k < kNodes; ++k) {
      int m[3] = {n[0], n[1], n[2]};
      m[axis] = k;
      x[k] = nodeAt(origin, h, cell, m)[axis];
    }
    for (int f = 0; f < found; ++f)
      for (int k = 0; k < kNodes; ++k)
        if (std::abs(at[f] - x[k]) <= tol) return false;  // a node (nearly) on the surface
    const bool start = inside[n[0]][n[1]][n[2]];
    for (int k = 1; k < kNodes; ++k) {
      int crossings = 0;
      for (int f = 0; f < found; ++f) crossings += at[f] > x[0] && at[f] < x[k];
      int m[3] = {n[0], n[1], n[2]};
      m[axis] = k;
      inside[m[0]][m[1]][m[2]] = start != ((crossings & 1) != 0);
    }
    return true;
  };
  inside[0][0][0] = startInside;
  if (!walk(2, first)) return false;
  for (int c = 0; c < kNodes; ++c)
    if (!walk(1, {0, 0, c})) return false;
  for (int c = 0; c < kNodes; ++c)
    for (int b = 0; b < kNodes; ++b)
      if (!walk(0, {0, b, c})) return false;
  for (int c = 0; c < kNodes; ++c) {
    uint64_t layer = 0;
    for (int b = 0; b < kNodes; ++b)
      for (int a = 0; a < kNodes; ++a)
        if (!inside[a][b][c]) layer |= uint64_t(1) << (a + kNodes * b);
    (*outside)[static_cast<size_t>(c)] = layer;
  }
  return true;
}

}  // namespace vp

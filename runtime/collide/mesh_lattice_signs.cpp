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

enum class Crossing { None, At, Undecided };

// Whether the line through (pu, pv) in the (axis + 1, axis + 2) plane, along `axis`, crosses
// triangle `id`, and where along `axis` (*at); Undecided when it passes too near an edge.
Crossing crossLine(const PreparedCollider& mesh, int id, int axis, double pu, double pv, double tol, double* at) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const Eigen::Vector3i& t = mesh.triangles[id];
  const Eigen::Vector3d& a = mesh.worldVertices[t[0]];
  const Eigen::Vector3d& b = mesh.worldVertices[t[1]];
  const Eigen::Vector3d& c = mesh.worldVertices[t[2]];
  if (std::max({a[u], b[u], c[u]}) < pu - tol || std::min({a[u], b[u], c[u]}) > pu + tol ||
      std::max({a[v], b[v], c[v]}) < pv - tol || std::min({a[v], b[v], c[v]}) > pv + tol)
    return Crossing::None;
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
  if (!(std::abs(area) > tol * std::max({la, lb, lc}))) return Crossing::Undecided;
  const double s = area > 0.0 ? 1.0 : -1.0;
  if (s * ea < -tol * la || s * eb < -tol * lb || s * ec < -tol * lc) return Crossing::None;  // clearly outside
  if (!(s * ea > tol * la && s * eb > tol * lb && s * ec > tol * lc)) return Crossing::Undecided;
  *at = (ea * a[axis] + eb * b[axis] + ec * c[axis]) / area;
  return Crossing::At;
}

// The signs of the nodes at x[0 .. 8) along a line (inside[0] known), from the crossings
// at[0 .. found); false when a crossing is (nearly) at a node: a node on the surface.
bool signsAlong(const double* at, int found, const double* x, double tol, bool* inside) {
  for (int f = 0; f < found; ++f)
    for (int k = 0; k < kNodes; ++k)
      if (std::abs(at[f] - x[k]) <= tol) return false;
  for (int k = 1; k < kNodes; ++k) {
    int crossings = 0;
    for (int f = 0; f < found; ++f) crossings += at[f] > x[0] && at[f] < x[k];
    inside[k] = inside[0] != ((crossings & 1) != 0);
  }
  return true;
}

}  // namespace

bool latticeNodesOutsideMesh(const PreparedCollider& mesh, const Eigen::Vector3d& origin, double h,
                             const Eigen::Vector3d& cell, std::array<uint64_t, 8>* outside) {
  const double tol = kTolerance * h;
  // Node coordinates per axis: a node's coordinate along one axis does not depend on the others.
  double coord[3][kNodes];
  for (int k = 0; k < kNodes; ++k) {
    const Eigen::Vector3d p = nodeAt(origin, h, cell, {k, k, k});
    for (int d = 0; d < 3; ++d) coord[d][k] = p[d];
  }
  const Eigen::Vector3d lo(coord[0][0], coord[1][0], coord[2][0]);
  const Eigen::Vector3d queryLo = lo.array() - tol;
  const Eigen::Vector3d queryHi = Eigen::Vector3d(coord[0][kNodes - 1], coord[1][kNodes - 1], coord[2][kNodes - 1]).array() + tol;
  int ids[kMaxTriangles];
  int count = 0;
  bool overflow = false;
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
  double at[kMaxTriangles];
  // Along one line through the cell: its crossings, then its nodes' signs from the first's.
  auto walk = [&](int axis, double pu, double pv, bool* inside) {
    int found = 0;
    for (int k = 0; k < count; ++k) {
      const Crossing c = crossLine(mesh, ids[k], axis, pu, pv, tol, &at[found]);
      if (c == Crossing::Undecided) return false;
      found += c == Crossing::At;
    }
    return signsAlong(at, found, coord[axis], tol, inside);
  };
  // The z-line at a = b = 0, then the y-lines at a = 0: the x-lines' first nodes.
  bool column[kNodes], first[kNodes][kNodes];  // first[c][b]: node (0, b, c)
  column[0] = startInside;
  if (!walk(2, coord[0][0], coord[1][0], column)) return false;
  for (int c = 0; c < kNodes; ++c) {
    first[c][0] = column[c];
    if (!walk(1, coord[2][c], coord[0][0], first[c])) return false;
  }
  // The x-lines, triangle by triangle over the lines its shadow reaches (far fewer tests than
  // every triangle against every line).
  constexpr int kMaxLineCrossings = 16;
  double lineAt[kNodes][kNodes][kMaxLineCrossings];  // [c][b]
  int lineFound[kNodes][kNodes] = {};
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3i& t = mesh.triangles[ids[k]];
    const Eigen::Vector3d& a = mesh.worldVertices[t[0]];
    const Eigen::Vector3d& b = mesh.worldVertices[t[1]];
    const Eigen::Vector3d& c = mesh.worldVertices[t[2]];
    const double yLo = std::min({a.y(), b.y(), c.y()}) - 2.0 * tol, yHi = std::max({a.y(), b.y(), c.y()}) + 2.0 * tol;
    const double zLo = std::min({a.z(), b.z(), c.z()}) - 2.0 * tol, zHi = std::max({a.z(), b.z(), c.z()}) + 2.0 * tol;
    for (int cz = 0; cz < kNodes; ++cz) {
      if (coord[2][cz] < zLo || coord[2][cz] > zHi) continue;
      for (int by = 0; by < kNodes; ++by) {
        if (coord[1][by] < yLo || coord[1][by] > yHi) continue;
        double x = 0.0;
        const Crossing cross = crossLine(mesh, ids[k], 0, coord[1][by], coord[2][cz], tol, &x);
        if (cross == Crossing::Undecided) return false;
        if (cross == Crossing::None) continue;
        int& found = lineFound[cz][by];
        if (found == kMaxLineCrossings) return false;
        lineAt[cz][by][found++] = x;
      }
    }
  }
  for (int cz = 0; cz < kNodes; ++cz) {
    uint64_t layer = 0;
    for (int by = 0; by < kNodes; ++by) {
      bool inside[kNodes];
      inside[0] = first[cz][by];
      if (!signsAlong(lineAt[cz][by], lineFound[cz][by], coord[0], tol, inside)) return false;
      for (int ax = 0; ax < kNodes; ++ax)
        if (!inside[ax]) layer |= uint64_t(1) << (ax + kNodes * by);
    }
    (*outside)[static_cast<size_t>(cz)] = layer;
  }
  return true;
}

}  // namespace vp

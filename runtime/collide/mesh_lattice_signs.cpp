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

// A triangle seen along one axis: what a line-crossing test reads, computed once per triangle
// and axis rather than once per line (a cell's lines test each nearby triangle dozens of times).
struct ProjectedTriangle {
  double uLo, uHi, vLo, vHi;        // its shadow's bounds in the (axis + 1, axis + 2) plane
  double du[3], dv[3], fu[3], fv[3];  // edge k runs from vertex (k + 1) % 3 to (k + 2) % 3, from (fu, fv)
  double length[3];                 // the edges' lengths in the projection
  double area;                      // twice the shadow's signed area
  double along[3];                  // the vertices' coordinates along the axis
  bool edgeOn;                      // the line nearly in its plane: no decision
};

ProjectedTriangle project(const PreparedCollider& mesh, int id, int axis, double tol) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const Eigen::Vector3i& t = mesh.triangles[id];
  const Eigen::Vector3d* x[3] = {&mesh.worldVertices[t[0]], &mesh.worldVertices[t[1]], &mesh.worldVertices[t[2]]};
  const Eigen::Vector3d &a = *x[0], &b = *x[1], &c = *x[2];
  ProjectedTriangle p;
  p.uLo = std::min({a[u], b[u], c[u]});
  p.uHi = std::max({a[u], b[u], c[u]});
  p.vLo = std::min({a[v], b[v], c[v]});
  p.vHi = std::max({a[v], b[v], c[v]});
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d &from = *x[(k + 1) % 3], &to = *x[(k + 2) % 3];
    p.du[k] = to[u] - from[u];
    p.dv[k] = to[v] - from[v];
    p.fu[k] = from[u];
    p.fv[k] = from[v];
    p.length[k] = std::sqrt(p.du[k] * p.du[k] + p.dv[k] * p.dv[k]);  // no overflow at world scales: hypot is slower
    p.along[k] = (*x[k])[axis];
  }
  p.area = (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
  p.edgeOn = !(std::abs(p.area) > tol * std::max({p.length[0], p.length[1], p.length[2]}));
  return p;
}

// Whether the line through (pu, pv), along the triangle's projection axis, crosses it, and
// where along the axis (*at); Undecided when it passes too near an edge.
Crossing crossLine(const ProjectedTriangle& p, double pu, double pv, double tol, double* at) {
  if (p.uHi < pu - tol || p.uLo > pu + tol || p.vHi < pv - tol || p.vLo > pv + tol) return Crossing::None;
  // A triangle seen edge-on within reach of p: no decision.
  if (p.edgeOn) return Crossing::Undecided;
  // Twice the signed area of (edge k, p): the edge's length times p's signed distance from it.
  double e[3];
  for (int k = 0; k < 3; ++k) e[k] = p.du[k] * (pv - p.fv[k]) - p.dv[k] * (pu - p.fu[k]);
  const double s = p.area > 0.0 ? 1.0 : -1.0;
  if (s * e[0] < -tol * p.length[0] || s * e[1] < -tol * p.length[1] || s * e[2] < -tol * p.length[2])
    return Crossing::None;  // clearly outside
  if (!(s * e[0] > tol * p.length[0] && s * e[1] > tol * p.length[1] && s * e[2] > tol * p.length[2]))
    return Crossing::Undecided;
  *at = (e[0] * p.along[0] + e[1] * p.along[1] + e[2] * p.along[2]) / p.area;
  return Crossing::At;
}

// The signs along a line of nodes at x[0 .. 8) (increasing), from the first's and the crossings
// at[0 .. found): bit k of *inside is set where node k is inside. False when a crossing is
// (nearly) at a node: a node on the surface.
bool signsAlong(const double* at, int found, const double* x, double tol, bool firstInside, uint32_t* inside) {
  uint32_t mask = firstInside ? 0xffu : 0u;
  for (int f = 0; f < found; ++f) {
    int before = 0;  // nodes before the crossing
    for (int k = 0; k < kNodes; ++k) {
      if (std::abs(at[f] - x[k]) <= tol) return false;
      before += x[k] < at[f];
    }
    if (before > 0) mask ^= (0xffu << before) & 0xffu;  // a crossing before node 0 flips nothing
  }
  *inside = mask;
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
  ProjectedTriangle projected[kMaxTriangles];
  auto projectAll = [&](int axis) {
    for (int k = 0; k < count; ++k) projected[k] = project(mesh, ids[k], axis, tol);
  };
  // Along one line through the cell: its crossings, then its nodes' signs from the first's.
  auto walk = [&](int axis, double pu, double pv, bool firstInside, uint32_t* inside) {
    int found = 0;
    for (int k = 0; k < count; ++k) {
      const Crossing c = crossLine(projected[k], pu, pv, tol, &at[found]);
      if (c == Crossing::Undecided) return false;
      found += c == Crossing::At;
    }
    return signsAlong(at, found, coord[axis], tol, firstInside, inside);
  };
  // The z-line at a = b = 0, then the y-lines at a = 0: the x-lines' first nodes.
  uint32_t column = 0, first[kNodes] = {};  // bit c of column: node (0, 0, c); bit b of first[c]: node (0, b, c)
  projectAll(2);
  if (!walk(2, coord[0][0], coord[1][0], startInside, &column)) return false;
  projectAll(1);
  for (int c = 0; c < kNodes; ++c)
    if (!walk(1, coord[2][c], coord[0][0], (column >> c) & 1u, &first[c])) return false;
  // The x-lines, triangle by triangle over the lines its shadow reaches (far fewer tests than
  // every triangle against every line).
  constexpr int kMaxLineCrossings = 16;
  double lineAt[kNodes][kNodes][kMaxLineCrossings];  // [c][b]
  int lineFound[kNodes][kNodes] = {};
  for (int k = 0; k < count; ++k) {
    const ProjectedTriangle p = project(mesh, ids[k], 0, tol);
    const double yLo = p.uLo - 2.0 * tol, yHi = p.uHi + 2.0 * tol;
    const double zLo = p.vLo - 2.0 * tol, zHi = p.vHi + 2.0 * tol;
    for (int cz = 0; cz < kNodes; ++cz) {
      if (coord[2][cz] < zLo || coord[2][cz] > zHi) continue;
      for (int by = 0; by < kNodes; ++by) {
        if (coord[1][by] < yLo || coord[1][by] > yHi) continue;
        double x = 0.0;
        const Crossing cross = crossLine(p, coord[1][by], coord[2][cz], tol, &x);
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
      uint32_t inside = 0;
      if (!signsAlong(lineAt[cz][by], lineFound[cz][by], coord[0], tol, (first[cz] >> by) & 1u, &inside)) return false;
      layer |= uint64_t(~inside & 0xffu) << (kNodes * by);
    }
    (*outside)[static_cast<size_t>(cz)] = layer;
  }
  return true;
}

}  // namespace vp

#include "geometry/stuffing_offset.h"

#include "geometry/isosurface_stuffing.h"
#include "geometry/segment_surface_crossing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace vp {
namespace {

// The signed distance along the unit normal n from p to the nearest surface crossing within
// `reach` either way (positive outward); 0 when there is none.
double gapAlong(const SurfaceMesh& surface, const RefitBvh& bvh, const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                double reach) {
  double t = 1.0;
  const double out = firstSurfaceCrossing(bvh, surface, p, p + reach * n, &t) ? reach * t : reach;
  // Inward, only a crossing nearer than the outward one counts.
  if (out > 0.0 && firstSurfaceCrossing(bvh, surface, p, p - out * n, &t) && t < 1.0) return -out * t;
  return out < reach ? out : 0.0;
}

// The mesh's boundary triangles, oriented outward: the tet faces no other tet shares. Only
// faces of surface vertices can be on the boundary (a lattice vertex inside the surface has
// every lattice tet around it filled), so only those are sorted.
std::vector<std::array<int32_t, 3>> boundaryTriangles(const TetMesh& mesh, const Array<uint8_t>& onSurface) {
  std::vector<std::pair<std::array<int32_t, 3>, std::array<int32_t, 3>>> faces;  // sorted, oriented
  for (const auto& tet : mesh.tets)
    for (const auto& f : kTetFaces) {
      const std::array<int32_t, 3> oriented{{tet[f[0]], tet[f[1]], tet[f[2]]}};
      if (!onSurface[static_cast<size_t>(oriented[0])] || !onSurface[static_cast<size_t>(oriented[1])] ||
          !onSurface[static_cast<size_t>(oriented[2])])
        continue;
      std::array<int32_t, 3> key = oriented;
      std::sort(key.begin(), key.end());
      faces.emplace_back(key, oriented);
    }
  std::sort(faces.begin(), faces.end());
  std::vector<std::array<int32_t, 3>> boundary;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].first == faces[i].first) ++j;
    if (j == i + 1) boundary.push_back(faces[i].second);
    i = j;
  }
  return boundary;
}

// Each mesh vertex's tets, as offsets into one list (CSR).
struct VertexTets {
  Array<int32_t> first, tets;
};

VertexTets vertexTets(const TetMesh& mesh) {
  VertexTets vt;
  vt.first.assign(mesh.vertices.size() + 1, 0);
  for (const auto& t : mesh.tets)
    for (int32_t v : t) ++vt.first[static_cast<size_t>(v) + 1];
  for (size_t v = 0; v < mesh.vertices.size(); ++v) vt.first[v + 1] += vt.first[v];
  vt.tets.resize(static_cast<size_t>(vt.first.back()));
  Array<int32_t> next(vt.first.begin(), vt.first.end() - 1);
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    for (int32_t v : mesh.tets[t]) vt.tets[static_cast<size_t>(next[static_cast<size_t>(v)]++)] = static_cast<int32_t>(t);
  return vt;
}

// The largest and the smallest cosine of the six dihedral angles of the positive tet x[t]: the
// angle at an edge is pi less the angle between the outward normals of the two faces there.
void dihedralCosineRange(const Array<Eigen::Vector3d>& x, const std::array<int32_t, 4>& t, double* maxCos,
                         double* minCos) {
  Eigen::Vector3d n[4];
  for (int f = 0; f < 4; ++f) {
    const auto& face = kTetFaces[static_cast<size_t>(f)];
    const Eigen::Vector3d& a = x[t[face[0]]];
    n[f] = (x[t[face[1]]] - a).cross(x[t[face[2]]] - a).normalized();
  }
  *maxCos = -2.0;
  *minCos = 2.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const double c = -n[i].dot(n[j]);
      *maxCos = std::max(*maxCos, c);
      *minCos = std::min(*minCos, c);
    }
}

double cosDegrees(double degrees) { return std::cos(degrees * M_PI / 180.0); }

// Whether every tet of v is positive with its dihedral angles inside the stuffing bounds, and
// not pushed past kOffsetMinDihedralDegrees / kOffsetMaxDihedralDegrees unless it was already
// past them (then no further). In cosines (the smallest angle has the largest cosine).
bool tetsOfVertexAcceptable(const TetMesh& mesh, const VertexTets& vt, int32_t v, const Array<double>& maxCosBefore,
                            const Array<double>& minCosBefore) {
  static const double stuffingMin = cosDegrees(kStuffingMinDihedralDegrees);
  static const double stuffingMax = cosDegrees(kStuffingMaxDihedralDegrees);
  static const double offsetMin = cosDegrees(kOffsetMinDihedralDegrees);
  static const double offsetMax = cosDegrees(kOffsetMaxDihedralDegrees);
  const auto& x = mesh.vertices;
  for (int32_t i = vt.first[static_cast<size_t>(v)]; i < vt.first[static_cast<size_t>(v) + 1]; ++i) {
    const size_t tet = static_cast<size_t>(vt.tets[static_cast<size_t>(i)]);
    const auto& t = mesh.tets[tet];
    if (!(signedTetVolume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]) > 0.0)) return false;
    double maxCos, minCos;
    dihedralCosineRange(x, t, &maxCos, &minCos);
    if (!(maxCos < stuffingMin && minCos > stuffingMax)) return false;
    if (maxCos > std::max(offsetMin, maxCosBefore[tet]) || minCos < std::min(offsetMax, minCosBefore[tet]))
      return false;
  }
  return true;
}

// The mean signed gap between triangle (a, b, c) and the surface along its unit normal n: the
// edge-midpoint rule, exact for a quadratic gap.
double meanGap(const SurfaceMesh& surface, const RefitBvh& bvh, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
               const Eigen::Vector3d& c, const Eigen::Vector3d& n, double reach) {
  return (gapAlong(surface, bvh, 0.5 * (a + b), n, reach) + gapAlong(surface, bvh, 0.5 * (b + c), n, reach) +
          gapAlong(surface, bvh, 0.5 * (c + a), n, reach)) /
         3.0;
}

}  // namespace

void offsetStuffedBoundary(const SurfaceMesh& surface, const RefitBvh& bvh, double h, const Array<uint8_t>& onSurface,
                           TetMesh* mesh, StuffingOffsetReport* reportOut) {
  StuffingOffsetReport report;
  const auto& x = mesh->vertices;
  // Per mesh vertex: the sums of A_f g_f and of A_f n_f over its boundary triangles.
  Array<double> lost(x.size(), 0.0);
  Array<Eigen::Vector3d> normal(x.size(), Eigen::Vector3d::Zero());
  Array<uint8_t> onBoundary(x.size(), 0);
  for (const auto& tri : boundaryTriangles(*mesh, onSurface)) {
    const Eigen::Vector3d &a = x[tri[0]], &b = x[tri[1]], &c = x[tri[2]];
    const Eigen::Vector3d areaNormal = 0.5 * (b - a).cross(c - a);
    const double area = areaNormal.norm();
    if (!(area > 0.0)) continue;
    const double gap = meanGap(surface, bvh, a, b, c, areaNormal / area, kOffsetReachCells * h);
    for (int32_t v : tri) {
      lost[static_cast<size_t>(v)] += area * gap;
      normal[static_cast<size_t>(v)] += areaNormal;
      onBoundary[static_cast<size_t>(v)] = 1;
    }
  }

  // The angles of the tets the moves can change, before any move.
  const VertexTets vt = vertexTets(*mesh);
  Array<double> maxCosBefore(mesh->tets.size(), -2.0), minCosBefore(mesh->tets.size(), 2.0);
  for (size_t v = 0; v < x.size(); ++v) {
    if (!onBoundary[v]) continue;
    for (int32_t i = vt.first[v]; i < vt.first[v + 1]; ++i) {
      const size_t t = static_cast<size_t>(vt.tets[static_cast<size_t>(i)]);
      if (maxCosBefore[t] < -1.5) dihedralCosineRange(x, mesh->tets[t], &maxCosBefore[t], &minCosBefore[t]);
    }
  }
  const double cap = kMaxOffsetCells * h;
  for (size_t v = 0; v < x.size(); ++v) {
    const double length = normal[v].norm();
    if (!onBoundary[v] || !(length > 0.0) || lost[v] == 0.0) continue;
    const double offset = std::clamp(lost[v] / length, -cap, cap);
    const Eigen::Vector3d from = mesh->vertices[v];
    const Eigen::Vector3d move = (offset / length) * normal[v];
    double scale = 1.0;
    for (int halving = 0;; ++halving) {
      mesh->vertices[v] = from + scale * move;
      if (tetsOfVertexAcceptable(*mesh, vt, static_cast<int32_t>(v), maxCosBefore, minCosBefore)) break;
      if (halving == kOffsetHalvings) {
        mesh->vertices[v] = from;
        scale = 0.0;
        break;
      }
      scale *= 0.5;
    }
    if (scale < 1.0) ++report.limitedVertices;
    if (scale > 0.0) {
      ++report.movedVertices;
      report.maxOffset = std::max(report.maxOffset, scale * std::fabs(offset) / h);
    }
  }
  if (reportOut != nullptr) *reportOut = report;
}

}  // namespace vp

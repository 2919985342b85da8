#include "geometry/embedding.h"

#include "geometry/closest_point_on_triangle.h"

#include "geometry/tet_spatial_grid.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

namespace vp {
namespace {

// Round-off slack for "inside": a point on a face shared by two tets gets a coordinate of
// about -1e-16 in both; 1e-12 accepts that with margin and is far below any real outside
// distance in barycentric units (1e-12 of the tet's height).
constexpr double kInsideTolerance = 1e-12;

// Affine map from a point to its barycentric coordinates (1..3 solved, 0 = 1 - sum).
struct TetFrame {
  Eigen::Vector3d origin;
  Eigen::Matrix3d inverse;  // inverse of [b - a, c - a, d - a]

  std::array<double, 4> barycentric(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d l = inverse * (p - origin);
    return {{1.0 - (l[0] + l[1] + l[2]), l[0], l[1], l[2]}};
  }
};

double minCoordinate(const std::array<double, 4>& l) { return std::min({l[0], l[1], l[2], l[3]}); }


// Distance from p to the boundary of tet t: the distance to the tet when p is outside.
double boundaryDistance(const TetMesh& mesh, int32_t t, const Eigen::Vector3d& p) {
  const auto& tet = mesh.tets[t];
  double best = std::numeric_limits<double>::infinity();
  for (const auto& face : kTetFaces) {
    const Eigen::Vector3d q = closestPointOnTriangle(p, mesh.vertices[tet[face[0]]], mesh.vertices[tet[face[1]]],
                                                mesh.vertices[tet[face[2]]]);
    best = std::min(best, (q - p).squaredNorm());
  }
  return std::sqrt(best);
}

}  // namespace

double pointTetDistance(const TetMesh& mesh, int32_t t, const Eigen::Vector3d& p) {
  const auto& tet = mesh.tets[t];
  const auto l = tetBarycentric(mesh.vertices[tet[0]], mesh.vertices[tet[1]], mesh.vertices[tet[2]],
                                mesh.vertices[tet[3]], p);
  if (minCoordinate(l) >= 0.0) return 0.0;
  return boundaryDistance(mesh, t, p);
}

namespace {

Status checkMesh(const TetMesh& mesh) {
  if (mesh.tets.empty() || mesh.vertices.empty())
    return fail(Status::InvalidArgument, "embedPoints: the tet mesh is empty (%zu vertices, %zu tets)",
                mesh.vertices.size(), mesh.tets.size());
  const int64_t n = static_cast<int64_t>(mesh.vertices.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    for (int k = 0; k < 4; ++k)
      if (mesh.tets[t][k] < 0 || mesh.tets[t][k] >= n)
        return fail(Status::InvalidArgument, "embedPoints: tet %zu corner %d is vertex %d, outside [0, %lld)", t, k,
                    mesh.tets[t][k], static_cast<long long>(n));
  for (size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      return fail(Status::InvalidArgument, "embedPoints: tet mesh vertex %zu has a non-finite coordinate", v);
  return Status::Ok;
}

Status embed(const TetMesh& mesh, const Array<Eigen::Vector3d>& points, Array<EmbeddedPoint>* out,
             EmbeddingReport* report) {
  VP_TRY(checkMesh(mesh));
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      return fail(Status::InvalidArgument, "embedPoints: point %zu has a non-finite coordinate (%g, %g, %g)", i,
                  points[i].x(), points[i].y(), points[i].z());

  std::vector<TetFrame> frames(mesh.tets.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    const Eigen::Vector3d& a = mesh.vertices[tet[0]];
    Eigen::Matrix3d edges;
    edges << mesh.vertices[tet[1]] - a, mesh.vertices[tet[2]] - a, mesh.vertices[tet[3]] - a;
    bool invertible = false;
    double determinant = 0.0;
    edges.computeInverseAndDetWithCheck(frames[t].inverse, determinant, invertible, 0.0);
    if (!invertible || !frames[t].inverse.allFinite())
      return fail(Status::InvalidArgument, "embedPoints: tet %zu is degenerate (volume %g); validate the mesh first", t,
                  determinant / 6.0);
    frames[t].origin = a;
  }

  TetSpatialGrid grid;
  grid.build(mesh);
  // Bounding boxes give a cheap lower bound that skips most exact distance computations
  // in the nearest-tet search.
  Array<Eigen::Vector3d> boxLo(mesh.tets.size()), boxHi(mesh.tets.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    boxLo[t] = boxHi[t] = mesh.vertices[tet[0]];
    for (int k = 1; k < 4; ++k) {
      boxLo[t] = boxLo[t].cwiseMin(mesh.vertices[tet[k]]);
      boxHi[t] = boxHi[t].cwiseMax(mesh.vertices[tet[k]]);
    }
  }

  Array<EmbeddedPoint> result(points.size());
  Array<int64_t> seenBy(mesh.tets.size(), -1);  // last point that tested a tet
  EmbeddingReport summary;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    const auto cell = grid.cellOf(p);
    // 1. Containing tet: its bounding box contains p, so it is listed in p's cell.
    int32_t best = -1;
    double bestDepth = -std::numeric_limits<double>::infinity();
    std::array<double, 4> bestCoordinates{};
    grid.forEachTetInCell(cell, [&](int32_t t) {
      const auto l = frames[t].barycentric(p);
      const double depth = minCoordinate(l);
      if (depth > bestDepth) {
        bestDepth = depth;
        best = t;
        bestCoordinates = l;
      }
    });
    if (best >= 0 && bestDepth >= -kInsideTolerance) {
      result[i] = {best, bestCoordinates};
      continue;
    }
    // 2. Nearest tet: rings of cells around p until no unvisited cell can be closer.
    double bestDistance = std::numeric_limits<double>::infinity();
    best = -1;
    for (int64_t ring = 0;; ++ring) {
      grid.forEachCellInRing(cell, ring, [&](const std::array<int64_t, 3>& c) {
        grid.forEachTetInCell(c, [&](int32_t t) {
          if (seenBy[t] == static_cast<int64_t>(i)) return;
          seenBy[t] = static_cast<int64_t>(i);
          // '>' (not '>=') so that ties still reach the index tie-break below.
          if ((p - p.cwiseMax(boxLo[t]).cwiseMin(boxHi[t])).norm() > bestDistance) return;
          // p is in no tet (phase 1), so its distance to a tet is the distance to its boundary.
          const double d = boundaryDistance(mesh, t, p);
          if (d < bestDistance || (d == bestDistance && t < best)) {
            bestDistance = d;
            best = t;
          }
        });
      });
      // Unvisited cells are all farther than this bound; once every cell is visited the
      // bound is infinite and best >= 0 (the mesh is not empty), so the loop ends.
      if (best >= 0 && grid.distanceBeyondRing(p, cell, ring) >= bestDistance) break;
    }
    result[i] = {best, frames[best].barycentric(p)};
    ++summary.outsidePoints;
    summary.maxOutsideDistance = std::max(summary.maxOutsideDistance, bestDistance);
  }
  *out = std::move(result);
  if (report != nullptr) *report = summary;
  return Status::Ok;
}

}  // namespace

std::array<double, 4> tetBarycentric(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                     const Eigen::Vector3d& d, const Eigen::Vector3d& p) {
  Eigen::Matrix3d edges;
  edges << b - a, c - a, d - a;
  const Eigen::Vector3d l = edges.partialPivLu().solve(p - a);
  return {{1.0 - (l[0] + l[1] + l[2]), l[0], l[1], l[2]}};
}

Status embedPoints(const TetMesh& mesh, const Array<Eigen::Vector3d>& points, Array<EmbeddedPoint>* out,
                   EmbeddingReport* report) {
  if (out == nullptr) return fail(Status::InvalidArgument, "embedPoints: out is null");
  try {
    return embed(mesh, points, out, report);
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "embedPoints: out of memory for %zu tets and %zu points", mesh.tets.size(),
                points.size());
  }
}

Status evaluateEmbedded(const Array<std::array<int32_t, 4>>& tets, const Array<Eigen::Vector3d>& deformed,
                        const Array<EmbeddedPoint>& embedding, Array<Eigen::Vector3d>* positions) {
  if (positions == nullptr) return fail(Status::InvalidArgument, "evaluateEmbedded: positions is null");
  const int64_t numTets = static_cast<int64_t>(tets.size());
  const int64_t numVertices = static_cast<int64_t>(deformed.size());
  // Checked before anything is written, so that the output is unchanged on error.
  for (size_t i = 0; i < embedding.size(); ++i) {
    const int32_t t = embedding[i].tet;
    if (t < 0 || t >= numTets)
      return fail(Status::InvalidArgument, "evaluateEmbedded: point %zu refers to tet %d, outside [0, %lld)", i, t,
                  static_cast<long long>(numTets));
    for (int k = 0; k < 4; ++k)
      if (tets[t][k] < 0 || tets[t][k] >= numVertices)
        return fail(Status::InvalidArgument,
                    "evaluateEmbedded: point %zu: tet %d uses vertex %d but only %lld deformed positions were given", i,
                    t, tets[t][k], static_cast<long long>(numVertices));
  }
  try {
    positions->resize(embedding.size());
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "evaluateEmbedded: out of memory for %zu points", embedding.size());
  }
  for (size_t i = 0; i < embedding.size(); ++i) {
    const auto& tet = tets[embedding[i].tet];
    const auto& l = embedding[i].barycentric;
    (*positions)[i] = l[0] * deformed[tet[0]] + l[1] * deformed[tet[1]] + l[2] * deformed[tet[2]] +
                      l[3] * deformed[tet[3]];
  }
  return Status::Ok;
}

Status computeVertexNormals(const Array<Eigen::Vector3d>& positions,
                            const Array<std::array<int32_t, 3>>& triangles, Array<Eigen::Vector3d>* normals) {
  if (normals == nullptr) return fail(Status::InvalidArgument, "computeVertexNormals: normals is null");
  const int64_t n = static_cast<int64_t>(positions.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (triangles[t][k] < 0 || triangles[t][k] >= n)
        return fail(Status::InvalidArgument, "computeVertexNormals: triangle %zu corner %d is vertex %d, outside [0, %lld)",
                    t, k, triangles[t][k], static_cast<long long>(n));
  try {
    normals->assign(positions.size(), Eigen::Vector3d::Zero());
  } catch (const std::bad_alloc&) {
    return fail(Status::OutOfMemory, "computeVertexNormals: out of memory for %zu vertices", positions.size());
  }
  for (const auto& tri : triangles) {
    // The unnormalized cross product is twice the area times the unit normal: summing it
    // is exactly the area weighting.
    const Eigen::Vector3d weighted =
        (positions[tri[1]] - positions[tri[0]]).cross(positions[tri[2]] - positions[tri[0]]);
    for (int32_t v : tri) (*normals)[v] += weighted;
  }
  for (auto& normal : *normals) {
    const double length = normal.norm();
    normal = length > 0.0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d::Zero();
  }
  return Status::Ok;
}

}  // namespace vp

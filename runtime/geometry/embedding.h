// Embedding of a render mesh (or any points) in a simulation tet mesh: each point is
// stored as "tet index + 4 barycentric coordinates" and follows the tets as they deform.
//
// The record does not depend on the element degree: a degree-n Bernstein-Bezier element
// evaluates its polynomial at the same barycentric coordinates (the 4 coordinates are the
// arguments of every BB basis function), so the same records serve degree 1, 2 and 3.
#pragma once

#include "core/allocator.h"
#include "core/status.h"
#include "geometry/tet_mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace vp {

struct EmbeddedPoint {
  int32_t tet = -1;
  // Barycentric coordinates with respect to the tet's corners 0..3 in the rest mesh;
  // they sum to 1. All >= 0 (up to round-off) when the point lies in the tet; a point
  // outside every tet keeps the (extrapolated, partly negative) coordinates of the nearest
  // tet, so it moves with that tet's affine map.
  std::array<double, 4> barycentric{{0.0, 0.0, 0.0, 0.0}};
};

struct EmbeddingReport {
  int64_t outsidePoints = 0;        // points that lie in no tet (nearest tet used)
  double maxOutsideDistance = 0.0;  // largest distance from such a point to its tet
};

// Finds, for each point, a tet containing it (barycentric coordinates >= -1e-12; among
// several, e.g. on a shared face, the one where the point is deepest inside) or, failing
// that, the nearest tet. O((T + P) * tets per grid cell) with a uniform grid; deterministic.
// `mesh` must be valid (see validateAndRepairTetMesh). Errors: InvalidArgument for an empty
// or invalid mesh or a non-finite point (named by index). `*out` is unchanged on error;
// `report` may be null.
Status embedPoints(const TetMesh& mesh, const Array<Eigen::Vector3d>& points,
                   Array<EmbeddedPoint>* out, EmbeddingReport* report = nullptr);

// Degree-1 evaluation: position of each embedded point for the deformed tet vertex
// positions `deformed` (same numbering as the mesh the embedding was made on).
// InvalidArgument, naming the point, if a record's tet or its vertices are out of range.
Status evaluateEmbedded(const Array<std::array<int32_t, 4>>& tets, const Array<Eigen::Vector3d>& deformed,
                        const Array<EmbeddedPoint>& embedding, Array<Eigen::Vector3d>* positions);

// Per-vertex normals of a triangle mesh: the sum of the incident faces' normals weighted
// by their areas (the raw cross products), normalized. A vertex with no incident area
// gets the zero vector. InvalidArgument, naming the triangle, for an out-of-range index.
Status computeVertexNormals(const Array<Eigen::Vector3d>& positions,
                            const Array<std::array<int32_t, 3>>& triangles, Array<Eigen::Vector3d>* normals);

// Euclidean distance from `p` to tet `t` (0 inside); indices must be valid.
double pointTetDistance(const TetMesh& mesh, int32_t t, const Eigen::Vector3d& p);

// Barycentric coordinates of `p` in the tet (a, b, c, d) (sum 1, extrapolated outside).
std::array<double, 4> tetBarycentric(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                     const Eigen::Vector3d& d, const Eigen::Vector3d& p);

}  // namespace vp

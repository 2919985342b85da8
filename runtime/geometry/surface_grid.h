// The cubic grid a surface tetrahedralizer lays over a closed triangle surface: its argument
// checks and its size, shared by the voxel and the stuffing meshers so that `resolution`
// means the same in both.
#pragma once

#include "core/status.h"
#include "geometry/surface_mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace vp {

struct SurfaceGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // min corner of cell (0, 0, 0)
  double cellSize = 0.0;
  std::array<int32_t, 3> cells{{0, 0, 0}};
};

constexpr int kMaxSurfaceGridResolution = 1024;
constexpr int64_t kMaxSurfaceGridCells = int64_t(1) << 24;

// `resolution` cells along the longest axis of the bounding box of the vertices the triangles
// use; as many cells of the same size along the other axes as cover the box, the grid centred
// on it (it may miss the box by round-off, about 1e-9 of a cell, on each side).
// Errors (InvalidArgument, messages prefixed by `caller`): resolution outside
// [1, kMaxSurfaceGridResolution], more than kMaxSurfaceGridCells cells, an empty surface, an
// index out of range, a non-finite coordinate, a bounding box that is a single point.
// `*out` is unchanged on error.
Status makeSurfaceGrid(const SurfaceMesh& surface, int resolution, const char* caller, SurfaceGrid* out);

}  // namespace vp

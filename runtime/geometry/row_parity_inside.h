// Which points of a regular grid lie inside a closed triangle surface, by ray parity along the
// grid's x rows: one ray per row instead of one per point, so the cost is O(rows + triangles +
// crossings). Shared by the voxel and the stuffing tetrahedralizers.
#pragma once

#include "core/allocator.h"
#include "core/status.h"
#include "geometry/surface_mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace vp {

// The points origin + spacing * (i + offset, j + offset, k + offset) for 0 <= i < count[0],
// 0 <= j < count[1], 0 <= k < count[2].
struct SampleGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double spacing = 1.0;
  double offset = 0.0;
  std::array<int64_t, 3> count{{0, 0, 0}};
};

// (*inside)[(k * count[1] + j) * count[0] + i] = 1 for a point inside `surface`, else 0 (a
// point exactly on the surface may get either). Exact for a closed surface: rays through a
// shared edge or vertex are decided by symbolic perturbation, so each crossing counts once.
// `surface` must have indices in range and finite coordinates. Errors: InvalidArgument
// prefixed by `caller` when a row crosses the surface an odd number of times (the surface is
// not closed); `*inside` is unchanged on error.
Status insideByRowParity(const SurfaceMesh& surface, const SampleGrid& grid, const char* caller,
                         Array<uint8_t>* inside);

}  // namespace vp

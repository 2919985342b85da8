// Builds a simulation mesh from a closed render surface: voxelize, then split every kept
// voxel into 6 tets. Coarse and robust rather than boundary-conforming: the render mesh is
// embedded in the result (see embedding.h), so the tets only need to cover it.
#pragma once

#include "core/status.h"
#include "geometry/surface_grid.h"
#include "geometry/surface_mesh.h"
#include "geometry/tet_mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace vp {

struct VoxelGrid : SurfaceGrid {
  int64_t keptCells = 0;     // = number of tets / 6
  int64_t surfaceCells = 0;  // kept because the surface passes through them
};

// `resolution`: number of cells along the longest axis of the surface's bounding box
// (surface_grid.h: 1..1024; at most 2^24 cells in all). A cell is kept if its centre is
// inside the surface or the surface passes through it, so the union of the tets contains the
// whole solid.
// Every cube is split into the same 6 tets around its (0,0,0)-(1,1,1) diagonal; the split
// is the same for every cube, so faces shared by neighbouring cubes are split the same way
// and the mesh is conforming. Vertices are shared between cubes, all tets are positively
// oriented, the output is deterministic (cells in z, y, x order; vertices in lattice order).
// Errors: InvalidArgument for a bad resolution, an empty/degenerate surface, out-of-range
// indices, non-finite coordinates, or a surface that is not closed. `*out` is unchanged on
// error; `grid` (may be null) describes the voxel grid on success.
Status tetrahedralizeVoxels(const SurfaceMesh& surface, int resolution, TetMesh* out, VoxelGrid* grid = nullptr);

}  // namespace vp

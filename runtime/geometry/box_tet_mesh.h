// A box filled with cubes, each split into 6 tets around its main diagonal (a Kuhn split:
// the same split for every cube, so neighbouring cubes conform). Used for the built-in box
// deformable of scene files, for vpBoxTetMesh, for tests against beam theory and for benchmarks.
#pragma once

#include <array>
#include <cstdint>

#include "core/math_types.h"
#include "core/status.h"
#include "geometry/tet_mesh.h"

namespace vp {

// Limits that scene files and the C ABI check before meshing: a side's cell count, and the
// total cell count, which keeps the mesh a deformable could plausibly use and its counts far
// inside int32.
constexpr int kMaxBoxCellsPerAxis = 512;
constexpr int64_t kMaxBoxCells = int64_t(1) << 21;

// cells[k] in [1, kMaxBoxCellsPerAxis], their product at most kMaxBoxCells, each side of `size`
// a length (core/physical_limits.h). Messages name the field: "cells[1] = 0: ...", "size.y = ...".
Status checkBoxTetMeshArgs(const std::array<int, 3>& cells, const Vec3& size);

// cells along x, y, z (each >= 1); the box spans [minCorner, minCorner + size]. Vertices are
// in lattice order (x fastest), all tets positively oriented; 6 * cx * cy * cz tets.
TetMesh makeBoxTetMesh(const std::array<int, 3>& cells, const Vec3& size, const Vec3& minCorner);

}  // namespace vp

// A box filled with cubes, each split into 6 tets around its main diagonal (a Kuhn split:
// the same split for every cube, so neighbouring cubes conform). Used for the built-in box
// deformable of scene files, for tests against beam theory and for benchmarks.
#pragma once

#include <array>

#include "core/math_types.h"
#include "geometry/tet_mesh.h"

namespace vp {

// cells along x, y, z (each >= 1); the box spans [minCorner, minCorner + size]. Vertices are
// in lattice order (x fastest), all tets positively oriented; 6 * cx * cy * cz tets.
TetMesh makeBoxTetMesh(const std::array<int, 3>& cells, const Vec3& size, const Vec3& minCorner);

}  // namespace vp

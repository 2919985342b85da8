// The boundary surface of a tet mesh: every triangle used by exactly one tet, oriented
// outwards. It is the default render mesh of a deformable built from tets alone.
#pragma once

#include "core/allocator.h"
#include "geometry/surface_mesh.h"
#include "geometry/tet_mesh.h"

namespace vp {

// The surface's vertices are the mesh vertices that lie on the boundary (renumbered
// compactly, in mesh order); surfaceToMeshVertex maps them back.
SurfaceMesh tetMeshBoundary(const TetMesh& mesh, Array<int32_t>* surfaceToMeshVertex = nullptr);

}  // namespace vp

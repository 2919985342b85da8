// One entry point for loading a simulation mesh from any supported volumetric format.
#pragma once

#include "core/status.h"
#include "geometry/tet_mesh.h"
#include "geometry/tet_mesh_validation.h"

#include <string>

namespace vp {

// Dispatches on the extension (case-insensitive): .msh -> readGmsh, .node/.ele -> readTetGen,
// .vtk -> readVtk; then runs validateAndRepairTetMesh (errors get the path as context).
// Unsupported for other extensions. `*out` is unchanged on error; `report` may be null.
Status readTetMeshFile(const std::string& path, TetMesh* out, TetMeshRepairReport* report = nullptr);

}  // namespace vp

// Reader for legacy VTK files (.vtk), ASCII, DATASET UNSTRUCTURED_GRID.
#pragma once

#include "core/status.h"
#include "geometry/tet_mesh.h"

#include <string>

namespace vp {

// Reads POINTS (float or double), CELLS and CELL_TYPES and keeps the cells of type 10
// (VTK_TETRA); other cell types are skipped. Both the classic CELLS layout
// (count-prefixed lists, file versions <= 4.2) and the OFFSETS/CONNECTIVITY layout of
// version 5.1 are read. POINT_DATA / CELL_DATA and what follows are ignored.
// Errors: Unsupported for BINARY files and other DATASET kinds, ParseError naming file and
// line otherwise. `*out` is unchanged on error; the mesh is not validated.
Status readVtk(const std::string& path, TetMesh* out);

}  // namespace vp

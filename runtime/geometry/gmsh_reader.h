// Reader for Gmsh .msh files, ASCII format versions 2.2 and 4.1.
#pragma once

#include "core/status.h"
#include "geometry/tet_mesh.h"

#include <string>

namespace vp {

// Reads the 4-node tetrahedra (element type 4) and the nodes of an ASCII .msh file.
// Other element types (points, lines, triangles, 10-node tets ...) are skipped; node tags
// may be any positive integers, not necessarily contiguous. Vertices keep file order; the
// mesh is not validated (see readTetMeshFile).
// Errors: IoError (cannot read), Unsupported (binary .msh, other versions),
// ParseError naming the file, line and what was expected. `*out` is unchanged on error.
Status readGmsh(const std::string& path, TetMesh* out);

}  // namespace vp

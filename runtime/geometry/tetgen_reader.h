// Reader for TetGen .node + .ele files.
#pragma once

#include "core/status.h"
#include "geometry/tet_mesh.h"

#include <string>

namespace vp {

// `path` is the .node file, the .ele file, or their common basename ("mesh" for
// mesh.node + mesh.ele). Points are numbered from 0 or 1, as the first point of the .node
// file says; numbering must then be consecutive. Attributes, boundary markers and region
// attributes are read and dropped. 10-node (second order) .ele files keep their 4 corner
// nodes. `*out` is unchanged on error; the mesh is not validated (see readTetMeshFile).
Status readTetGen(const std::string& path, TetMesh* out);

}  // namespace vp

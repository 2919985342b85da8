// A triangle surface mesh: render meshes and the input of the voxel tetrahedralizer.
#pragma once

#include "core/allocator.h"
#include "core/status.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vp {

struct SurfaceMesh {
  Array<Eigen::Vector3d> vertices;
  Array<std::array<int32_t, 3>> triangles;  // counter-clockwise seen from outside
};

// Loads any format assimp reads (OBJ, PLY, STL, glTF, FBX ...). Polygons are triangulated,
// identical vertices joined within each assimp mesh, and all meshes of the scene merged
// into one with their node transforms applied (a mesh instanced by several nodes appears
// once per instance). Points and lines are dropped.
// assimp runs isolated from the host (geometry/isolated_import.h): a file that crashes or
// hangs it is a ParseError. Only regular files are read.
// Errors: IoError (missing/unreadable file, not a regular file), ParseError (assimp could not
// import it, crashed or timed out on it, or no triangles, or a non-finite coordinate),
// OutOfMemory. `*out` is unchanged on error.
Status loadSurfaceMesh(const std::string& path, SurfaceMesh* out);

// The import itself, in this process: what loadSurfaceMesh runs in its isolated child.
Status importSurfaceMeshWithAssimp(const std::string& path, SurfaceMesh* out);

// Writes a Wavefront OBJ (used by tests and tools to hand generated surfaces to assimp).
Status writeSurfaceMeshObj(const SurfaceMesh& mesh, const std::string& path);

}  // namespace vp

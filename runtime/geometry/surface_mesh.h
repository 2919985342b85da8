// Triangle surface meshes, and loading them from any file format assimp reads.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math_types.h"
#include "core/status.h"

namespace vp {

struct SurfaceMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int32_t, 3>> triangles;
};

// Loads every mesh of the file's scene, with node transforms applied, triangulated and with
// identical vertices joined. IoError if unreadable, ParseError if it holds no triangles.
Status loadSurfaceMesh(const std::string& path, SurfaceMesh* out);

}  // namespace vp

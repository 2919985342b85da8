#include "geometry/tet_mesh_boundary.h"

#include <algorithm>
#include <map>

namespace vp {

SurfaceMesh tetMeshBoundary(const TetMesh& mesh, Array<int32_t>* surfaceToMeshVertex) {
  // Count each face by its sorted vertex triple; keep the oriented copy of single ones.
  struct FaceUse {
    int count = 0;
    std::array<int32_t, 3> oriented{};
  };
  std::map<std::array<int32_t, 3>, FaceUse> faces;
  for (const auto& tet : mesh.tets)
    for (const auto& f : kTetFaces) {
      std::array<int32_t, 3> tri{tet[f[0]], tet[f[1]], tet[f[2]]};
      std::array<int32_t, 3> key = tri;
      std::sort(key.begin(), key.end());
      FaceUse& use = faces[key];
      use.count++;
      use.oriented = tri;
    }
  SurfaceMesh surface;
  Array<int32_t> meshToSurface(mesh.vertices.size(), -1);
  Array<std::array<int32_t, 3>> triangles;
  for (const auto& [key, use] : faces)
    if (use.count == 1) triangles.push_back(use.oriented);
  // Deterministic vertex numbering: mesh order.
  for (const auto& t : triangles)
    for (int32_t v : t) meshToSurface[v] = 0;
  Array<int32_t> back;
  for (size_t v = 0; v < mesh.vertices.size(); ++v)
    if (meshToSurface[v] == 0) {
      meshToSurface[v] = static_cast<int32_t>(surface.vertices.size());
      surface.vertices.push_back(mesh.vertices[v]);
      back.push_back(static_cast<int32_t>(v));
    }
  for (const auto& t : triangles)
    surface.triangles.push_back({meshToSurface[t[0]], meshToSurface[t[1]], meshToSurface[t[2]]});
  if (surfaceToMeshVertex) *surfaceToMeshVertex = std::move(back);
  return surface;
}

}  // namespace vp

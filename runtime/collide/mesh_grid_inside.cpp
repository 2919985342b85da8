#include "collide/mesh_grid_inside.h"

#include "geometry/surface_mesh.h"

namespace vp {

Status meshGridInside(const PreparedCollider& mesh, const SampleGrid& grid, const char* caller,
                      Array<uint8_t>* inside) {
  SurfaceMesh surface;
  surface.vertices.assign(mesh.worldVertices.begin(), mesh.worldVertices.end());
  surface.triangles.resize(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    surface.triangles[t] = {mesh.triangles[t][0], mesh.triangles[t][1], mesh.triangles[t][2]};
  return insideByRowParity(surface, grid, caller, inside);
}

}  // namespace vp

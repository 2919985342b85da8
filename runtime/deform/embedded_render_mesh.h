// The fine render mesh embedded in a deformable's coarse tets: each vertex keeps the element
// it lies in and its barycentric coordinates there at rest (geometry/embedding.h), and moves
// with the element's BB polynomial of the node positions, so a coarse simulation mesh carries
// a detailed surface.
#pragma once

#include <cstdint>

#include "core/allocator.h"
#include "core/math_types.h"
#include "core/status.h"
#include "core/task_system.h"
#include "geometry/embedding.h"
#include "geometry/mesh_quality.h"
#include "geometry/refit_bvh.h"
#include "geometry/surface_mesh.h"
#include "geometry/tet_mesh.h"

namespace vp {

class EmbeddedRenderMesh {
 public:
  // `rest`'s vertices embedded in `mesh` (which must be valid); on failure the error of
  // embedPoints and nothing changes.
  Status build(const TetMesh& mesh, SurfaceMesh rest);

  // The vertices moved to the node positions x (3 per node) through the elements:
  // elementNodes holds nodesPerElement nodes per element in BB order for `degree`.
  void update(TaskSystem& tasks, int degree, int nodesPerElement, const Array<int32_t>& elementNodes,
              const Array<double>& x);
  // Positions and normals as saved (snapshot/actor_states.h).
  void restore(Array<Vec3>&& positions, Array<Vec3>&& normals);

  const SurfaceMesh& rest() const { return rest_; }
  const Array<Vec3>& positions() const { return positions_; }  // world frame
  const Array<Vec3>& normals() const { return normals_; }
  // The surface at its current positions as a BVH: built on the first request, refit on a
  // request after the positions moved (queries hold the world, so no two requests run at once).
  const RefitBvh& bvh() const;
  // The tet mesh's dihedral angles and volume against the surface's, at build.
  const TetMeshQuality& quality() const { return quality_; }

 private:
  SurfaceMesh rest_;
  TetMeshQuality quality_;
  Array<EmbeddedPoint> embedding_;
  Array<Vec3> positions_, normals_;
  uint64_t version_ = 0;  // counts moves of the positions
  mutable RefitBvh bvh_;
  mutable uint64_t bvhVersion_ = ~uint64_t(0);  // the version the BVH's boxes are of
};

}  // namespace vp

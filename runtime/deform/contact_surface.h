// A deformable's boundary as other deformables (and the body itself) touch it: the tet mesh's
// boundary triangles over the corner nodes, a bounding volume hierarchy over them that is
// refit to the nodes' positions once per step (its shape is built once: a deformable keeps
// its triangles), and which nodes share an element, so that self contact can leave out a
// node's own neighbourhood (a node always lies on the triangles around it).
#pragma once

#include <array>
#include <cstdint>

#include "core/allocator.h"
#include "core/math_types.h"
#include "geometry/refit_bvh.h"
#include "geometry/surface_mesh.h"

namespace vp {

class ContactSurface {
 public:
  // `boundary`'s vertex v is node vertexNode[v]; elementNodes holds nodesPerElement node ids
  // per element, whose first four are its corners.
  void build(const SurfaceMesh& boundary, const Array<int32_t>& vertexNode, const Array<int32_t>& elementNodes,
             int nodesPerElement, int32_t nodeCount);
  // The triangles' boxes at node positions x (3 per node).
  void refit(const Array<double>& x);

  const RefitBvh& bvh() const { return bvh_; }
  const Array<RefitBvh::Triangle>& triangles() const { return triangleNodes_; }  // node ids
  // Whether nodes a and b are the same node or corners of one element.
  bool neighbours(int32_t a, int32_t b) const;
  // More than one layer of elements: some corner node lies inside the body.
  bool hasInteriorNode() const { return hasInteriorNode_; }

 private:
  Array<int32_t> vertexNode_;
  Array<RefitBvh::Triangle> triangles_;      // over boundary vertices, for the BVH
  Array<RefitBvh::Triangle> triangleNodes_;  // the same over node ids
  Array<Vec3> positions_;                    // boundary vertices, this step
  RefitBvh bvh_;
  Array<int32_t> neighbourStart_, neighbourList_;  // per node, sorted corner neighbours
  bool hasInteriorNode_ = false;
};

}  // namespace vp

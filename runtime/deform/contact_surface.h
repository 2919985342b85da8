// A deformable's boundary as other deformables (and the body itself) touch it: the tet mesh's
// boundary triangles over the corner nodes, a bounding volume hierarchy over them that is
// refit to the nodes' positions once per step (its shape is built once: a deformable keeps
// its triangles), and which nodes share an element, so that self contact can leave out a
// node's own neighbourhood (a node always lies on the triangles around it). Each triangle's
// box is grown by how far its corners move in the coming step in a frame moving with the
// surface's mean velocity, so a node's search covers only its own motion and not the body's
// fastest node's, and a body falling fast does not search its whole self: a search against
// the surface takes its motion in that frame too (frameVelocity). The nodes' normals tell a
// node lying on a triangle from one beside it (at a box's edge, on the face round the corner).
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
  // The triangles' boxes at node positions x (3 per node), each grown by h times its fastest
  // corner's speed in v (3 per node) relative to frameVelocity.
  void refit(const Array<double>& x, const Array<double>& v, double h);

  const RefitBvh& bvh() const { return bvh_; }
  // The mean velocity of the surface's nodes at the last refit: the frame its boxes move with.
  const Vec3& frameVelocity() const { return frameVelocity_; }
  const Array<RefitBvh::Triangle>& triangles() const { return triangleNodes_; }  // node ids
  // The corner nodes that share an element with node a (a itself included when it is a
  // corner), sorted: [first, last).
  struct NodeList {
    const int32_t* first = nullptr;
    const int32_t* last = nullptr;
  };
  NodeList neighbourList(int32_t a) const;
  int32_t nodeCount() const { return static_cast<int32_t>(neighbourStart_.empty() ? 0 : neighbourStart_.size() - 1); }
  // Node a's outward surface normal at the last refit: the area-weighted mean of its boundary
  // triangles' (unit); zero for a node on no boundary triangle (a higher degree's control point).
  const Vec3& nodeNormal(int32_t a) const { return nodeNormals_[static_cast<size_t>(a)]; }
  // More than one layer of elements: some corner node lies inside the body.
  bool hasInteriorNode() const { return hasInteriorNode_; }

 private:
  Array<int32_t> vertexNode_;
  Array<RefitBvh::Triangle> triangles_;      // over boundary vertices, for the BVH
  Array<RefitBvh::Triangle> triangleNodes_;  // the same over node ids
  Array<Vec3> positions_;                    // boundary vertices, this step
  Array<double> margins_;                    // per triangle, this step
  Array<Vec3> nodeNormals_;                  // per node, this step
  Vec3 frameVelocity_ = Vec3::Zero();
  RefitBvh bvh_;
  Array<int32_t> neighbourStart_, neighbourList_;  // per node, sorted corner neighbours
  bool hasInteriorNode_ = false;
};

}  // namespace vp

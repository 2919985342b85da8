// Covered (solid) area fraction of one axis-aligned MAC face against collider shapes.
//
// A face is the square { x : x[axis] = centre[axis], |x[a1]-centre[a1]| <= h/2,
// |x[a2]-centre[a2]| <= h/2 } with a1 = (axis+1)%3, a2 = (axis+2)%3 (in-plane coordinates
// (u, v) = (x[a1], x[a2]), a right-handed frame with the face normal).
//
// Methods per shape (the files face_coverage_<family>.cpp):
//   plane, box, convex hull  exact: the face square is clipped (Sutherland-Hodgman) by the
//                            half-planes that the solid's half-spaces cut out of the face plane;
//   sphere                   exact: disc-rectangle area in closed form (circular segments);
//   capsule, cylinder        exact chord lengths along face lines, integrated adaptively with a
//                            guaranteed bound from the concavity of the chord function
//                            (error < kCoverageTolerance of the face area);
//   triangle mesh            exact: Green's theorem over the mesh's cross-section segments;
//   several colliders        exact by inclusion-exclusion for convex polyhedra and at most
//                            one sphere; otherwise a rigorous quadtree on min of the signed
//                            distances (error < kCoverageTolerance), see coveredFractionUnion().
//
// Hot path: coveredFraction(const PreparedCollider&, ...) allocates nothing. Shape data that
// needs precomputation (hull planes, mesh BVH, world-space parameters) lives in
// PreparedCollider, built once per shape and refreshed with setPose() when the body moves.
#pragma once

#include "core/allocator.h"
#include "core/status.h"
#include "collide/collider_shape.h"

#include <Eigen/Core>
#include <vector>

namespace vp {

// Guaranteed bound on |computed - exact| covered fraction for the non-closed-form paths.
constexpr double kCoverageTolerance = 1e-3;
// Most half-spaces a box/hull may have (fixed-size clipping buffers, no allocation).
constexpr int kMaxConvexPlanes = 256;

struct AxisFace {
  int axis = 0;                                   // normal axis 0, 1, 2
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double h = 1.0;                                 // side length
};

struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1.0);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-1.0);  // empty by default
  bool empty() const { return (lo.array() > hi.array()).any(); }
  bool overlaps(const Aabb& o) const {
    return !empty() && !o.empty() && (lo.array() <= o.hi.array()).all() &&
           (o.lo.array() <= hi.array()).all();
  }
};

Aabb faceBounds(const AxisFace& face);

// Bounding volume hierarchy over a triangle mesh's world-space triangles (mesh shapes only).
struct TriangleBvh {
  struct Node {
    Eigen::Vector3d lo, hi;
    int first = 0, count = 0;  // leaf: triangles order[first, first+count)
    int left = -1, right = -1; // inner node children (count == 0)
  };
  Array<Node> nodes;
  std::vector<int> order;      // triangle ids in leaf order
};

// A shape ready for face queries: validated, world-space, with its acceleration data.
struct PreparedCollider {
  ColliderShape shape;          // the description (local data, pose, velocity)
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // world = rotation*local + t
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Aabb bounds;                  // world AABB (clamped to +-1e30 for half-spaces)
  Eigen::Vector3d boundCentre = Eigen::Vector3d::Zero();   // bounding sphere (finite shapes)
  double boundRadius = 0.0;

  // Plane, box, hull: world half-spaces n.x <= d with unit n (n in xyz, d in w).
  Array<Eigen::Vector4d> localPlanes;
  Array<Eigen::Vector4d> worldPlanes;

  // Triangle mesh: world vertices, outward-oriented triangles, BVH.
  Array<Eigen::Vector3d> worldVertices;
  Array<Eigen::Vector3i> triangles;
  TriangleBvh bvh;

  // A deforming surface (a deformable's boundary, setDeformingSurface): one world velocity
  // per vertex, and a count of its moves, so that a reader can tell it moved without
  // comparing vertices. Empty and 0 for a rigid shape.
  Array<Eigen::Vector3d> vertexVelocities;
  // Their mean: what the fluid's faces deep inside the surface take (face_fraction_field.h).
  Eigen::Vector3d meanVertexVelocity = Eigen::Vector3d::Zero();
  uint64_t surfaceMoves = 0;
};

// Validates `shape` (finite numbers, positive sizes, hull non-degenerate and at most
// kMaxConvexPlanes faces, mesh closed) and builds `out`. Changes nothing on failure.
Status prepareCollider(const ColliderShape& shape, PreparedCollider* out);

// Moves a prepared collider (mesh: rebuilds world vertices and BVH, O(n log n)).
Status setColliderPose(PreparedCollider* collider, const Eigen::Quaterniond& rotation,
                       const Eigen::Vector3d& translation);
// Puts back a pose that setColliderPose set before (a saved world state): the rotation is
// taken as it is, already normalized, so the collider comes out bitwise as it was.
void restoreColliderPose(PreparedCollider* collider, const Eigen::Quaterniond& unitRotation,
                         const Eigen::Vector3d& translation);

// A closed triangle mesh that deforms (a deformable's boundary): prepares it from its
// vertices (world frame, identity pose) and velocities, or moves a prepared one to new ones
// (same count; rebuilds the BVH). The mesh's validity (closed, not flat) is checked by the
// prepare only: a deformable's boundary keeps its topology.
Status prepareDeformingSurface(const Array<Eigen::Vector3d>& vertices, const Array<Eigen::Vector3i>& triangles,
                               PreparedCollider* out);
void setDeformingSurface(PreparedCollider* collider, const Array<Eigen::Vector3d>& vertices,
                         const Array<Eigen::Vector3d>& velocities);

// The velocity of the solid's material at (or, for a deforming surface, nearest to) x:
// rigid v + w x (x - c); a deforming surface's vertex velocities interpolated at the
// surface point closest to x.
Eigen::Vector3d solidVelocityAt(const PreparedCollider& collider, const Eigen::Vector3d& x);
// A bound on the speed of any of the solid's points (the fluid's sub-step rule).
double solidSpeedBound(const PreparedCollider& collider);

// Covered area fraction in [0,1] of `face` by one collider. No allocation.
double coveredFraction(const PreparedCollider& collider, const AxisFace& face);

// The covered fraction as coveredFraction gives it and, for a triangle mesh (a deforming
// surface included), the centroid of the covered part, exact (first moments by Green's
// theorem, face_coverage_mesh.cpp). The centroid is the face's centre where nothing is
// covered, and for any other shape. No allocation.
double coveredFractionAndCentroid(const PreparedCollider& collider, const AxisFace& face, Eigen::Vector3d* centroid);

// For a deforming surface (vertexVelocities set): the covered fraction as coveredFraction
// gives it and the surface's velocity where it crosses the face, the mean over its trace on
// the face (the segments where it meets the face's square) weighted by length: the velocity of
// the boundary between the covered part and the open one. Where the trace has no length
// (nothing covered, all of it, or the surface only touching the face's edge) *velocity is
// left as it is and *traced is false. No allocation.
double coveredFractionAndTraceVelocity(const PreparedCollider& surface, const AxisFace& face,
                                       Eigen::Vector3d* velocity, bool* traced);

// Convenience for one-off queries and tests: prepares `shape` (allocates); returns NaN when
// the shape is invalid (vp::lastError() says why).
double coveredFraction(const ColliderShape& shape, const AxisFace& face);

// Covered fraction of the union of several colliders on one face. One collider touching the
// face (after conservative rejects) -> its exact path; any collider covering the whole face
// -> 1; deforming surfaces -> their coverages added to the union of the rest (a deformable's
// contacts keep solids out of it, so the parts do not overlap; where they do, by a contact's
// penetration, the sum counts that sliver twice); up to four convex polyhedra and at most one
// sphere -> exact (inclusion-exclusion of clipped polygons); otherwise a quadtree over the
// face on the union's signed distance (min over colliders), refined until its rigorous error
// bound is below kCoverageTolerance.
double coveredFractionUnion(const PreparedCollider* const* colliders, int count,
                            const AxisFace& face);

// A 1-Lipschitz function with the sign of the signed distance (negative inside): exact SDF
// for sphere, box, capsule, cylinder, plane; max of face planes for a hull (exact inside,
// a lower bound outside); for a mesh, exact unsigned distance with a ray-parity sign.
double signedDistanceBound(const PreparedCollider& collider, const Eigen::Vector3d& x);

// Whether x lies inside the solid (for a mesh, by ray parity alone: cheaper than the
// signed distance when only the sign is wanted).
bool solidContains(const PreparedCollider& collider, const Eigen::Vector3d& x);

// Conservative classification of a face against one collider:
// -1: fully outside (covered 0), +1: fully inside (covered 1), 0: needs exact work.
int classifyFace(const PreparedCollider& collider, const AxisFace& face);

}  // namespace vp

// Open fractions and solid normal velocities of all MAC faces of a grid, from colliders.
//
// Grid: cell (i, j, k), 0 <= i < nx, ..., spans origin + h * [i, i+1] x [j, j+1] x [k, k+1].
// Face arrays (structure of arrays, one per normal axis):
//   axis 0 (u-faces): (nx+1) * ny * nz, face (i, j, k) at x = origin.x + i h,
//                     index i + (nx+1) * (j + ny * k)
//   axis 1 (v-faces): nx * (ny+1) * nz, face at y = origin.y + j h,
//                     index i + nx * (j + (ny+1) * k)
//   axis 2 (w-faces): nx * ny * (nz+1), face at z = origin.z + k h,
//                     index i + nx * (j + ny * k)
// i.e. always i + dimX * (j + dimY * k) with the face-count dimensions of that axis.
//
// open[a][f]          in [0, 1]: the part of face f not inside any collider.
// solidVelocity[a][f] the area-weighted normal (component a) velocity of the colliders over the
//                     covered part, 0 where the face is fully open. The rigid velocity
//                     v + w x (x - c) is linear in x, so its mean over the covered part is its
//                     value at the covered part's centroid; that centroid is approximated from
//                     the coverage of the face's four quadrants (exact for faces covered
//                     uniformly per quadrant; error <= |w| h / 2), and skipped (any point is
//                     exact) when w = 0. A deforming surface (a deformable's boundary) gives
//                     a face it cuts its vertex velocities interpolated along its trace on
//                     the face and averaged by length (collide/face_coverage.h,
//                     coveredFractionAndTraceVelocity): the velocity of the boundary between
//                     the covered part and the open one, the one the fluid's flux through the
//                     face sees move, found in the same pass over the triangles as the
//                     coverage. A face it covers whole takes the velocity of the surface point
//                     nearest its centre when a cell beside it has an open face, else (no
//                     fluid cell reads it) the surface's mean vertex velocity, which spares
//                     the nearest-point search for the body's interior. Faces covered by
//                     several colliders average the colliders' values (each at the surface
//                     point nearest its covered part's centroid) weighted by their coverage.
#pragma once

#include "core/allocator.h"
#include "collide/face_coverage.h"
#include "core/slab_passes.h"
#include "core/status.h"

#include <array>
#include <vector>

namespace vp {

struct MacGridSpec {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double h = 1.0;
  int nx = 0, ny = 0, nz = 0;
};

struct FaceFractionField {
  MacGridSpec grid;
  Array<double> open[3];
  Array<double> solidVelocity[3];

  // Face-count dimensions of axis a: (nx + (a == 0), ny + (a == 1), nz + (a == 2)).
  Eigen::Vector3i faceDims(int axis) const;
  size_t faceIndex(int axis, int i, int j, int k) const;
  AxisFace face(int axis, int i, int j, int k) const;
};

// Sizes the arrays for `grid` and sets every face open (1) with zero solid velocity.
Status initFaceFractionField(const MacGridSpec& grid, FaceFractionField* field);

// Full recompute: faces outside every collider's bounding box are set open; faces inside
// some box are computed from all colliders.
Status computeFaceFractions(const PreparedCollider* const* colliders, int count,
                            FaceFractionField* field);

// The boxes an update after a move recomputes: the boxes before and after, or, when they
// overlap, the box around both and an empty one (a collider moving a little per step, a paddle
// or a deformable's surface, then has its overlap recomputed once, not twice).
std::array<Aabb, 2> boxesToUpdate(const Aabb& oldBounds, const Aabb& newBounds);

// Incremental update after colliders moved: recomputes (from all current colliders) only the
// faces touching boxesToUpdate(oldBounds, newBounds) (e.g. the moved collider's boxes before
// and after the move). Gives the same result as computeFaceFractions when every change lies
// in them.
Status updateFaceFractions(const PreparedCollider* const* colliders, int count,
                           const Aabb& oldBounds, const Aabb& newBounds,
                           FaceFractionField* field);

// The same two as passes of bounded slices (core/slab_passes.h), for a fluid step spread
// over frames: one unit per row of faces, rows in parallel (a face's value depends on the
// colliders only, so where slabs are cut changes nothing). The collider array, the colliders
// and the field must stay as they are, but for these passes, until the passes have run.
Status addFaceFractionPasses(SlabPasses& passes, const PreparedCollider* const* colliders, int count,
                             FaceFractionField* field);
Status addFaceFractionUpdatePasses(SlabPasses& passes, const PreparedCollider* const* colliders, int count,
                                   const Aabb& oldBounds, const Aabb& newBounds, FaceFractionField* field);

}  // namespace vp

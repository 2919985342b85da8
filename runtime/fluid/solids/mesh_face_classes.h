// Which faces of a recomputed box a closed triangle mesh covers whole or not at all, decided
// for the whole box at once instead of by each face's exact coverage (face_coverage_mesh.cpp),
// which gathers the mesh's segments over a column above every face: for a deformable's
// surface, recomputed every fluid step over its whole bounding box, most faces lie deep inside
// or beside it.
//
// A face whose square no triangle's bounding box touches lies wholly inside or wholly outside
// the closed mesh, and its centre says which: by ray parity along rows of face centres
// (geometry/row_parity_inside.h), one ray per row. Every other face is Touched and takes the
// exact path. The classes are exact, so a face gets the coverage the exact path would give,
// but 0 and 1 exactly where that path's rounding may leave a last bit.
#pragma once

#include <cstdint>

#include "core/allocator.h"
#include "fluid/solids/face_box.h"

namespace vp {

enum class FaceClass : uint8_t { Outside = 0, Inside = 1, Touched = 2 };

struct MeshFaceClasses {
  const PreparedCollider* mesh = nullptr;
  FaceBox boxes[3];
  Array<uint8_t> classes[3];  // per face of boxes[axis], in its numbering
  // Touched for a face outside the boxes.
  FaceClass at(int axis, int i, int j, int k) const {
    const FaceBox& b = boxes[axis];
    if (classes[axis].empty() || !b.contains(i, j, k)) return FaceClass::Touched;
    return static_cast<FaceClass>(classes[axis][static_cast<size_t>(b.number(i, j, k))]);
  }
};

// Classifies the faces of `box` (facesAround per axis) against `mesh`, a prepared closed
// triangle mesh. Where the rows' crossings do not pair up (a mesh not closed), every face is
// Touched.
void classifyMeshFaces(const PreparedCollider& mesh, const FaceFractionField& field, const Aabb& box,
                       MeshFaceClasses* out);

// The faces in `out`'s boxes, for costing the classification as a pass.
int64_t classifiedFaces(const FaceFractionField& field, const Aabb& box);

}  // namespace vp

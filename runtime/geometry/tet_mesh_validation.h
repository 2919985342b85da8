// The gate every TetMesh passes before it becomes a simulation mesh.
#pragma once

#include "core/allocator.h"
#include "core/status.h"
#include "geometry/tet_mesh.h"

#include <cstdint>
#include <vector>

namespace vp {

struct TetMeshRepairReport {
  int64_t invertedTetsFixed = 0;      // tets whose corners 2 and 3 were swapped
  int64_t unusedVerticesRemoved = 0;  // vertices no tet referenced
  // newIndexOfOldVertex[old] = index after repair, or -1 for a removed vertex; lets a
  // caller carry per-vertex data (attributes, an embedding) through the renumbering.
  Array<int32_t> newIndexOfOldVertex;
};

// Rejects, with InvalidArgument and a message naming the tet/vertex index and the value:
//   - an empty mesh (no vertices or no tets) or one too large for int32 indices,
//   - a NaN or infinite coordinate,
//   - a tet index out of range, or a vertex repeated within one tet,
//   - a degenerate tet: |volume| <= kDegenerateVolumeTolerance * L^3, where L is the mean
//     tet edge length of the mesh.
// Repairs what has only one sensible repair:
//   - inverted tets (negative volume): corners 2 and 3 are swapped,
//   - vertices no tet uses are removed and the tet indices remapped (order kept).
// On error `mesh` is unchanged; `report` (may be null) is filled on success.
Status validateAndRepairTetMesh(TetMesh& mesh, TetMeshRepairReport* report);

// Relative volume tolerance for degenerate tets. Round-off in a tet volume computed from
// coordinates of magnitude M is about 1e-16 * M * L^2 (each edge vector carries an error
// of u*M); for meshes placed up to ~1e3 L from the origin that is ~1e-13 L^3, so 1e-10 is
// three orders above round-off. It is also far below any usable tet: a regular tet has
// volume 0.118 L^3, and a tet rejected here is flatter than height 6e-10 L over a face of
// size L — its stiffness would have a condition number beyond 1e9, i.e. it is a flat
// sliver, not a small element. Graded meshes with elements down to ~1e-3 L still pass.
constexpr double kDegenerateVolumeTolerance = 1e-10;

}  // namespace vp

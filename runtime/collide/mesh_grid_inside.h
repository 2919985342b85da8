// Which points of a regular grid lie inside a prepared closed triangle-mesh collider (a
// deforming surface included), at its current world vertices: ray parity along the grid's rows
// (geometry/row_parity_inside.h), one ray per row instead of one per point as solidContains
// casts. For the fluid's passes that ask it of every face or cell of a box around the mesh.
#pragma once

#include "collide/face_coverage.h"
#include "core/allocator.h"
#include "core/status.h"
#include "geometry/row_parity_inside.h"

namespace vp {

// insideByRowParity over `mesh`'s world triangles: (*inside)[(k * count[1] + j) * count[0] + i]
// is 1 inside, 0 outside (either on the surface). Errors as insideByRowParity's (a row that
// crosses an odd number of times: the mesh is not closed); `*inside` unchanged on error.
Status meshGridInside(const PreparedCollider& mesh, const SampleGrid& grid, const char* caller,
                      Array<uint8_t>* inside);

}  // namespace vp

// Whether a triangle surface bounds a solid: after welding vertices at identical positions
// (importers split them along texture seams), every directed edge (a, b) is used by exactly
// one triangle and its opposite (b, a) by exactly one other: a closed, consistently oriented
// surface. A surface that is not is a sheet, a mesh with holes, or one with non-manifold or
// flipped parts; no inside can be decided for it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/allocator.h"
#include "core/status.h"

namespace vp {

// InvalidArgument naming the first open or doubled edge by its (unwelded) vertex indices and
// position; `what` prefixes the message (e.g. "surface"). Triangle is std::array<int32_t, 3>
// (surface files) or Eigen::Vector3i (collider meshes); the indices must be in range.
template <class Triangle>
Status checkClosedSurface(const Array<Eigen::Vector3d>& vertices, const Array<Triangle>& triangles,
                          const char* what);

}  // namespace vp

// The faces of one axis that an update of a box recomputes (face_fraction_field.cpp), and a
// walk over them: shared by the recompute and the passes that classify faces ahead of it
// (mesh_face_classes.h).
#pragma once

#include <cmath>
#include <cstdint>

#include "collide/face_coverage.h"
#include "fluid/grid_index.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

// The faces of one axis touching a box, numbered along i first, then j, then k.
struct FaceBox {
  int axis = 0;
  int lo[3] = {0, 0, 0}, hi[3] = {-1, -1, -1};  // inclusive
  int64_t faces() const {
    int64_t n = 1;
    for (int d = 0; d < 3; ++d) n *= hi[d] < lo[d] ? 0 : hi[d] - lo[d] + 1;
    return n;
  }
  bool contains(int i, int j, int k) const {
    return i >= lo[0] && i <= hi[0] && j >= lo[1] && j <= hi[1] && k >= lo[2] && k <= hi[2];
  }
  // The face's number in the box (contains(i, j, k) must hold).
  int64_t number(int i, int j, int k) const {
    const int64_t nx = hi[0] - lo[0] + 1, ny = hi[1] - lo[1] + 1;
    return (i - lo[0]) + nx * ((j - lo[1]) + ny * static_cast<int64_t>(k - lo[2]));
  }
};

inline FaceBox facesAround(const FaceFractionField& field, const Aabb& box, int axis) {
  FaceBox r;
  r.axis = axis;
  if (box.empty()) return r;
  const MacGridSpec& g = field.grid;
  const Eigen::Vector3d lo = (box.lo - g.origin) / g.h, hi = (box.hi - g.origin) / g.h;
  const Eigen::Vector3i dims = field.faceDims(axis);
  for (int d = 0; d < 3; ++d) {
    // Faces of axis a sit at integer coordinates along a, span [j, j+1] across; one extra
    // face each side keeps the range conservative under rounding.
    const double l = (d == axis) ? std::ceil(lo[d]) - 1.0 : std::ceil(lo[d]) - 2.0;
    const double u = std::floor(hi[d]) + 1.0;
    r.lo[d] = clampIndex(l, 0, dims[d] - 1);
    r.hi[d] = clampIndex(u, 0, dims[d] - 1);
  }
  return r;
}

// visit(i, j, k) for faces [begin, end) of r, numbered along i first.
template <class Visit>
void forEachFaceOf(const FaceBox& r, int64_t begin, int64_t end, const Visit& visit) {
  const int64_t nx = r.hi[0] - r.lo[0] + 1, ny = r.hi[1] - r.lo[1] + 1;
  for (int64_t n = begin; n < end; ++n)
    visit(r.lo[0] + static_cast<int>(n % nx), r.lo[1] + static_cast<int>(n / nx % ny),
          r.lo[2] + static_cast<int>(n / nx / ny));
}

}  // namespace vp

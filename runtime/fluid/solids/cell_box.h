// The cells around a box that a face-fraction update touches, and a cell's faces by number:
// shared by the passes that tidy the fractions of recomputed regions (cut_cell_components.h,
// sliver_cells.h).
#pragma once

#include <cmath>
#include <cstddef>

#include "collide/face_coverage.h"
#include "fluid/grid_index.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

// A cell index box, inclusive.
struct CellBox {
  int lo[3], hi[3];
  bool empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
};

// Every cell that has a face recomputeBox (face_fraction_field.cpp) recomputes for `box`,
// grown by `margin` cells.
inline CellBox cellBoxAround(const MacGridSpec& g, const Aabb& box, int margin) {
  CellBox b;
  const Eigen::Vector3d lo = (box.lo - g.origin) / g.h, hi = (box.hi - g.origin) / g.h;
  const int cells[3] = {g.nx, g.ny, g.nz};
  for (int d = 0; d < 3; ++d) {
    b.lo[d] = clampIndex(std::ceil(lo[d]) - 2.0 - margin, 0, cells[d] - 1);
    b.hi[d] = clampIndex(std::floor(hi[d]) + 1.0 + margin, 0, cells[d] - 1);
  }
  return b;
}

// Open fraction of face (2 * axis + high) of cell (i, j, k).
inline double& faceOpen(FaceFractionField& f, int i, int j, int k, int face) {
  const int a = face / 2;
  Eigen::Vector3i fi(i, j, k);
  fi[a] += face & 1;
  return f.open[a][f.faceIndex(a, fi.x(), fi.y(), fi.z())];
}
inline double faceOpen(const FaceFractionField& f, int i, int j, int k, int face) {
  return faceOpen(const_cast<FaceFractionField&>(f), i, j, k, face);
}

// The sum of the open fractions of cell (i, j, k)'s six faces, in face order.
inline double cellOpenSum(const FaceFractionField& f, int i, int j, int k) {
  double sum = 0.0;
  for (int face = 0; face < 6; ++face) sum += faceOpen(f, i, j, k, face);
  return sum;
}

}  // namespace vp

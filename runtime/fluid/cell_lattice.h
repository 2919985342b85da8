// A grid's cells as the kernel bodies index them (gpu_kernels/cell_lattice.h).
#pragma once

#include <cstdint>

#include "fluid/solids/face_fraction_field.h"
#include "gpu_kernels/cell_lattice.h"

namespace vp {

inline kernels::CellLattice cellLattice(const MacGridSpec& s) {
  kernels::CellLattice g;
  g.n[0] = s.nx;
  g.n[1] = s.ny;
  g.n[2] = s.nz;
  g.stride[0] = 1;
  g.stride[1] = s.nx;
  g.stride[2] = static_cast<int64_t>(s.nx) * s.ny;
  g.h = s.h;
  return g;
}

// visit(c, i, j, k) for cells c in [begin, end), in cell order: the coordinates are stepped
// from cell to cell instead of divided out of every index (three integer divisions a cell,
// which cost more than the work of the cheap whole-grid passes that call this).
template <class Visit>
inline void forCellsInRange(const MacGridSpec& s, int64_t begin, int64_t end, const Visit& visit) {
  if (begin >= end) return;
  const int64_t plane = static_cast<int64_t>(s.nx) * s.ny;
  int i = static_cast<int>(begin % s.nx), j = static_cast<int>(begin / s.nx % s.ny),
      k = static_cast<int>(begin / plane);
  for (int64_t c = begin; c < end; ++c) {
    visit(c, i, j, k);
    if (++i < s.nx) continue;
    i = 0;
    if (++j < s.ny) continue;
    j = 0;
    ++k;
  }
}

}  // namespace vp

// A grid's cells as the kernel bodies index them (gpu_kernels/cell_lattice.h).
#pragma once

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

}  // namespace vp

// A staggered (MAC) velocity grid: face-centred normal velocities; cell-centred scalars
// (pressure, densities) are plain arrays in cell order that its helpers index and sample.
//
// Cells and faces use exactly the layout of FaceFractionField (face_fraction_field.h), so a
// face's velocity and its open fraction share one index:
//   cell (i, j, k), 0 <= i < nx ...            index i + nx * (j + ny * k)
//   axis-a face (i, j, k), dims faceDims(a)    index i + dimX * (j + dimY * k)
// velocity[a][f] is the a-component of the fluid velocity at the centre of face f.
//
// Domain sides: sides[2 * axis + 0] is the low side (x = origin.x for axis 0), sides[2 * axis
// + 1] the high side.
//   Wall  a closed, motionless wall: its boundary faces carry no flux (their velocity is 0
//         and the pressure operator treats them as closed, A_f = 0, whatever the colliders say).
//   Open  the fluid continues outside with p = 0 (Dirichlet ghost cell just outside): flow
//         may enter or leave through the open part (A_f from the colliders) of its faces.
#pragma once

#include <array>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"
#include "fluid/solids/face_fraction_field.h"
#include "gpu_kernels/mac_layout.h"

namespace vp {

enum class DomainSide : int { Wall = 0, Open = 1 };

struct MacGrid {
  MacGridSpec spec;
  std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                  DomainSide::Wall, DomainSide::Wall, DomainSide::Wall};
  Array<double> velocity[3];

  int64_t cellCount() const {
    return static_cast<int64_t>(spec.nx) * spec.ny * spec.nz;
  }
  size_t cellIndex(int i, int j, int k) const {
    return static_cast<size_t>(i) + static_cast<size_t>(spec.nx) * (j + static_cast<size_t>(spec.ny) * k);
  }
  Eigen::Vector3i faceDims(int axis) const {
    return Eigen::Vector3i(spec.nx + (axis == 0), spec.ny + (axis == 1), spec.nz + (axis == 2));
  }
  size_t faceIndex(int axis, int i, int j, int k) const {
    const Eigen::Vector3i d = faceDims(axis);
    return static_cast<size_t>(i) + static_cast<size_t>(d.x()) * (j + static_cast<size_t>(d.y()) * k);
  }
  Eigen::Vector3d cellCentre(int i, int j, int k) const {
    return spec.origin + spec.h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
  }
  Eigen::Vector3d faceCentre(int axis, int i, int j, int k) const {
    Eigen::Vector3d c = cellCentre(i, j, k);
    c[axis] -= 0.5 * spec.h;
    return c;
  }
  DomainSide side(int axis, bool highSide) const { return sides[2 * axis + (highSide ? 1 : 0)]; }
  // The layout kernel bodies index with (gpu_kernels/mac_layout.h).
  kernels::MacLayout layout() const {
    kernels::MacLayout l{spec.nx, spec.ny, spec.nz, {}};
    for (int s = 0; s < 6; ++s) l.wall[s] = sides[static_cast<size_t>(s)] == DomainSide::Wall;
    return l;
  }
  // True for a face on the domain boundary whose side is a Wall.
  bool isWallFace(int axis, int i, int j, int k) const {
    const int index = axis == 0 ? i : axis == 1 ? j : k;
    const int cells = axis == 0 ? spec.nx : axis == 1 ? spec.ny : spec.nz;
    if (index == 0) return side(axis, false) == DomainSide::Wall;
    if (index == cells) return side(axis, true) == DomainSide::Wall;
    return false;
  }

  // Trilinear interpolation of component `axis` from the face centres of that axis; points
  // outside the grid of face centres are clamped to it (constant extrapolation), which is
  // what semi-Lagrangian advection wants for back-traced points that leave the domain.
  double sampleComponent(int axis, const Eigen::Vector3d& point) const;
  Eigen::Vector3d sampleVelocity(const Eigen::Vector3d& point) const;
  // The velocity at the centre of cell (i, j, k): each component the mean of the cell's two
  // faces of that axis.
  Eigen::Vector3d cellVelocity(int i, int j, int k) const {
    Eigen::Vector3d u;
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3i hi(i, j, k);
      hi[a] += 1;
      u[a] = 0.5 * (velocity[a][faceIndex(a, i, j, k)] + velocity[a][faceIndex(a, hi.x(), hi.y(), hi.z())]);
    }
    return u;
  }
  // The same for a cell-centred scalar (cellCount() values in cell order: pressure, smoke
  // density, temperature ...).
  double sampleCellCentred(const double* values, const Eigen::Vector3d& point) const;
};

// Validates the spec (h > 0 and finite, positive cell counts, finite origin) and sizes the
// velocity arrays, all zero.
Status initMacGrid(const MacGridSpec& spec, const std::array<DomainSide, 6>& sides, MacGrid* grid);

// True when the face fraction field was computed for exactly this grid (same counts, h, origin).
bool sameGrid(const MacGridSpec& a, const MacGridSpec& b);

}  // namespace vp

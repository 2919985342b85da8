// The pressure around a solid, known where the fluid is and extended into the solid, so that
// its gradient (the rigid loads, pressure_forces.h) or its value on the solid's surface (a
// deformable's tractions, surface_pressure_load.h) can be read there.
//
// Over a box of cells around the solid's bounds, with two cells of margin (the extension reads
// two known cells outside the body): fluid cells keep the solve's pressure; cells every face of
// which is closed (solid cells) are filled layer by layer by linear extrapolation along each
// axis, averaged over the axes that have a known neighbour; the other cells are a liquid's air.
// Air is p = 0; given the level set, an air cell beside the liquid holds instead the ghost value
// that puts p = 0 on the surface between the two centres (p_air = p_liquid phi_air / phi_liquid,
// averaged over its liquid neighbours), the linear continuation of the liquid's pressure.
#pragma once

#include "collide/face_coverage.h"
#include "core/allocator.h"
#include "fluid/mac_grid.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

struct LocalPressure {
  Eigen::Vector3i lo, dims;
  Array<double> value;
  Array<int> layer;    // 0 known from the solve, k > 0 extended in layer k, -1 unknown
  Array<uint8_t> air;  // air of a liquid (not fluid)

  int64_t index(const Eigen::Vector3i& c) const {
    const Eigen::Vector3i l = c - lo;
    return l.x() + int64_t(dims.x()) * (l.y() + int64_t(dims.y()) * l.z());
  }
  bool contains(const Eigen::Vector3i& c) const {
    return ((c - lo).array() >= 0).all() && ((c - lo).array() < dims.array()).all();
  }
};

// Sets out's box (lo, dims) to the cells around `bounds`, with the margin the extension needs;
// false when they miss the grid.
bool cellBoxAround(const MacGridSpec& spec, const Aabb& bounds, LocalPressure* out);

// Fills `out` over the cells around `bounds`; false (out unchanged) when they miss the grid.
// `liquidPhi` (cell-centred, null for smoke or for air at p = 0) gives air cells their ghost
// values. Given `body`, the cells whose centres lie inside it are extended too, fluid or not:
// a cut cell whose fluid is a sliver beside the body has a pressure of no use at its centre
// (the solve leaves it free to take extreme values), and reading it there would put that
// value on the body's surface.
bool localPressureAround(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                         const double* pressure, const double* liquidPhi, const Aabb& bounds,
                         const PreparedCollider* body, LocalPressure* out);

}  // namespace vp

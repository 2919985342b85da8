// The pressure a liquid at rest would have under its current free surface: p = rho |g| d,
// with d the depth below the surface along gravity. What a body in the liquid feels of it
// depends only on where the body is, so a body can read it at every one of its own steps
// from the liquid's last completed step (deform/fluid_immersion.h), while the rest of the
// pressure is known only at the fluid's steps.
//
// The surface is found per column of cells along the grid axis gravity is most along: going
// up the column from its bottom, where the level set (free_surface.h's convention) first turns
// from liquid to air, linearly between the two cell centres. A point's surface height is the
// bilinear interpolation of the four columns around it. Exact for a flat surface under gravity
// along a grid axis. Why not the level set's own distance: it is clamped beyond a narrow band
// (level_set_redistance.h) and does not know the depth below it.
#pragma once

#include "collide/face_coverage.h"
#include "core/allocator.h"
#include "core/math_types.h"
#include "fluid/mac_grid.h"

namespace vp {

class HydrostaticPressure {
 public:
  // For points in `region` (a world box): the columns around it are found now. liquidPhi holds
  // one value per cell of `grid`.
  HydrostaticPressure(const MacGrid& grid, const double* liquidPhi, double density, const Vec3& gravity,
                      const Aabb& region);

  // The pressure at x; 0 above the surface.
  double at(const Vec3& x) const;

 private:
  MacGridSpec spec_;
  int axis_ = 1, across_[2] = {2, 0};  // gravity's axis and the two others
  double up_ = 1.0;                    // +1 when up is the axis' positive direction
  double weight_ = 0.0;                // rho |g|
  // The columns [lo_[0], lo_[0] + count_[0]) x [lo_[1], lo_[1] + count_[1]) over the region:
  // each one's surface as a coordinate along up (up_ times the world coordinate).
  int lo_[2] = {0, 0}, count_[2] = {0, 0};
  Array<double> height_;
};

}  // namespace vp

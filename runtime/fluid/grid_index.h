// A real grid coordinate (a bound in cells or faces, computed from a position that may lie far
// outside the grid, or be NaN) as an integer index in [lo, hi]. It converts only once the value
// is in range: a body that has flown to 1e30 m must not overflow an int.
#pragma once

namespace vp {

inline int clampIndex(double x, int lo, int hi) {
  if (!(x > lo)) return lo;  // also NaN
  if (x > hi) return hi;
  return static_cast<int>(x);
}

}  // namespace vp

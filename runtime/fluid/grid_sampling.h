// Trilinear interpolation on a regular lattice of samples, shared by the MAC grid's velocity
// and scalar sampling and by advection (which also needs the range of the 8 samples used,
// for MacCormack's clamp).
//
// Samples sit at lattice coordinates 0 .. dims-1 per axis, index i + dims.x * (j + dims.y * k).
// Coordinates outside the lattice are clamped to it (constant extrapolation), which is what
// semi-Lagrangian advection wants for back-traced points that leave the domain; NaN clamps
// to 0 instead of reaching an undefined float-to-int conversion.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace vp {

struct SampleRange {
  double lo = 0.0, hi = 0.0;
};

// `range` (optional) receives the smallest and largest of the samples with non-zero weight.
inline double trilinearSample(const double* values, const Eigen::Vector3i& dims, Eigen::Vector3d g,
                              SampleRange* range = nullptr) {
  int base[3];
  double weight[3];
  for (int d = 0; d < 3; ++d) {
    if (!(g[d] >= 0.0)) g[d] = 0.0;
    g[d] = std::min(g[d], static_cast<double>(dims[d] - 1));
    const int b = std::min(static_cast<int>(g[d]), std::max(dims[d] - 2, 0));
    base[d] = b;
    weight[d] = dims[d] > 1 ? g[d] - b : 0.0;
  }
  const size_t sx = 1, sy = static_cast<size_t>(dims[0]), sz = sy * static_cast<size_t>(dims[1]);
  const size_t step[3] = {dims[0] > 1 ? sx : 0, dims[1] > 1 ? sy : 0, dims[2] > 1 ? sz : 0};
  const double* p = values + base[0] * sx + base[1] * sy + base[2] * sz;
  const double c000 = p[0], c100 = p[step[0]], c010 = p[step[1]], c110 = p[step[0] + step[1]];
  const double c001 = p[step[2]], c101 = p[step[0] + step[2]], c011 = p[step[1] + step[2]],
               c111 = p[step[0] + step[1] + step[2]];
  if (range != nullptr) {
    range->lo = std::min({c000, c100, c010, c110, c001, c101, c011, c111});
    range->hi = std::max({c000, c100, c010, c110, c001, c101, c011, c111});
  }
  const double wx = weight[0], wy = weight[1], wz = weight[2];
  const double x00 = c000 + wx * (c100 - c000), x10 = c010 + wx * (c110 - c010);
  const double x01 = c001 + wx * (c101 - c001), x11 = c011 + wx * (c111 - c011);
  const double y0 = x00 + wy * (x10 - x00), y1 = x01 + wy * (x11 - x01);
  return y0 + wz * (y1 - y0);
}

}  // namespace vp

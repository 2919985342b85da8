// The hydrostatic pressure under a liquid's free surface (see hydrostatic_pressure.h).
#include "fluid/surface/hydrostatic_pressure.h"

#include <algorithm>
#include <cmath>

#include "fluid/grid_index.h"

namespace vp {

HydrostaticPressure::HydrostaticPressure(const MacGrid& grid, const double* liquidPhi, double density,
                                         const Vec3& gravity, const Aabb& region)
    : spec_(grid.spec) {
  const int dims[3] = {spec_.nx, spec_.ny, spec_.nz};
  gravity.cwiseAbs().maxCoeff(&axis_);
  across_[0] = (axis_ + 1) % 3;
  across_[1] = (axis_ + 2) % 3;
  up_ = gravity[axis_] > 0.0 ? -1.0 : 1.0;
  weight_ = density * gravity.norm();
  if (region.empty()) return;
  for (int c = 0; c < 2; ++c) {
    const int a = across_[c];
    const double lo = (region.lo[a] - spec_.origin[a]) / spec_.h - 0.5;
    const double hi = (region.hi[a] - spec_.origin[a]) / spec_.h + 0.5;
    lo_[c] = clampIndex(std::floor(lo), 0, dims[a] - 1);
    count_[c] = clampIndex(std::floor(hi), 0, dims[a] - 1) - lo_[c] + 1;
  }
  height_.assign(static_cast<size_t>(count_[0]) * count_[1], 0.0);
  const int n = dims[axis_];
  for (int q = 0; q < count_[1]; ++q)
    for (int p = 0; p < count_[0]; ++p) {
      int cell[3];
      cell[across_[0]] = lo_[0] + p;
      cell[across_[1]] = lo_[1] + q;
      // Cell centres and the column's ends as coordinates along up.
      auto along = [&](double index) { return up_ * (spec_.origin[axis_] + spec_.h * index); };
      auto phiAt = [&](int step) {
        cell[axis_] = up_ > 0.0 ? step : n - 1 - step;
        return liquidPhi[grid.cellIndex(cell[0], cell[1], cell[2])];
      };
      auto centre = [&](int step) { return along(up_ > 0.0 ? step + 0.5 : n - 0.5 - step); };
      double surface = std::min(along(0.0), along(static_cast<double>(n)));  // no liquid: the bottom
      bool wet = false;
      double below = 0.0;
      for (int step = 0; step < n; ++step) {
        const double phi = phiAt(step);
        if (phi < 0.0) {
          wet = true;
          surface = std::max(along(0.0), along(static_cast<double>(n)));  // liquid to the top
        } else if (wet) {
          surface = centre(step - 1) + spec_.h * below / (below - phi);
          break;
        }
        below = phi;
      }
      height_[static_cast<size_t>(p) + static_cast<size_t>(count_[0]) * q] = surface;
    }
}

double HydrostaticPressure::at(const Vec3& x) const {
  if (height_.empty()) return 0.0;
  int i0[2];
  double t[2];
  for (int c = 0; c < 2; ++c) {
    const double u = (x[across_[c]] - spec_.origin[across_[c]]) / spec_.h - 0.5 - lo_[c];
    i0[c] = clampIndex(std::floor(u), 0, std::max(0, count_[c] - 2));
    t[c] = count_[c] > 1 ? std::clamp(u - i0[c], 0.0, 1.0) : 0.0;
  }
  double surface = 0.0;
  for (int corner = 0; corner < 4; ++corner) {
    const int dp = corner & 1, dq = corner >> 1;
    const double w = (dp ? t[0] : 1.0 - t[0]) * (dq ? t[1] : 1.0 - t[1]);
    if (w == 0.0) continue;
    const int p = std::min(i0[0] + dp, count_[0] - 1), q = std::min(i0[1] + dq, count_[1] - 1);
    surface += w * height_[static_cast<size_t>(p) + static_cast<size_t>(count_[0]) * q];
  }
  return weight_ * std::max(0.0, surface - up_ * x[axis_]);
}

}  // namespace vp

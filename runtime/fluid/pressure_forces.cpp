// Pressure loads on colliders (see pressure_forces.h).
#include "fluid/pressure_forces.h"

#include <algorithm>
#include <cmath>

namespace vp {

PressureLoad pressureLoadOnCollider(const MacGrid& grid, const CutCellPoisson& op, const double* pressure,
                                    const PreparedCollider& collider, const Vec3& centre) {
  PressureLoad load;
  const MacGridSpec& s = grid.spec;
  const int n[3] = {s.nx, s.ny, s.nz};
  // Faces whose square can touch the collider's box.
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double l = (std::max(collider.bounds.lo[a], s.origin[a] - s.h) - s.origin[a]) / s.h;
    const double u = (std::min(collider.bounds.hi[a], s.origin[a] + (n[a] + 1) * s.h) - s.origin[a]) / s.h;
    lo[a] = std::max(0, static_cast<int>(std::floor(l)) - 1);
    hi[a] = std::min(n[a], static_cast<int>(std::ceil(u)) + 1);
    if (lo[a] > hi[a]) return load;
  }
  auto cellPressureAtFace = [&](Eigen::Vector3i cell, int a, int towardFace) -> double {
    const size_t c = grid.cellIndex(cell.x(), cell.y(), cell.z());
    if (!op.isFluid(c)) return 0.0;
    Eigen::Vector3i beyond = cell;
    beyond[a] -= towardFace;
    if (beyond[a] < 0 || beyond[a] >= n[a]) return pressure[c];
    const size_t b = grid.cellIndex(beyond.x(), beyond.y(), beyond.z());
    if (!op.isFluid(b)) return pressure[c];
    return pressure[c] + 0.5 * (pressure[c] - pressure[b]);
  };
  const double area = s.h * s.h;
  for (int a = 0; a < 3; ++a) {
    for (int k = lo[2]; k <= std::min(hi[2], n[2] - (a != 2)); ++k)
      for (int j = lo[1]; j <= std::min(hi[1], n[1] - (a != 1)); ++j)
        for (int i = lo[0]; i <= std::min(hi[0], n[0] - (a != 0)); ++i) {
          if (grid.isWallFace(a, i, j, k)) continue;
          AxisFace face;
          face.axis = a;
          face.h = s.h;
          face.centre = grid.faceCentre(a, i, j, k);
          const double covered = coveredFraction(collider, face);
          if (!(covered > 0.0)) continue;
          const Eigen::Vector3i high(i, j, k);
          Eigen::Vector3i low = high;
          low[a] -= 1;
          double p = 0.0;  // + p of the low cell (this is its high face), - p of the high cell
          if (low[a] >= 0) p += cellPressureAtFace(low, a, +1);
          if (high[a] < n[a]) p -= cellPressureAtFace(high, a, -1);
          Vec3 f = Vec3::Zero();
          f[a] = p * covered * area;
          load.force += f;
          load.torque += (face.centre - centre).cross(f);
        }
  }
  return load;
}

}  // namespace vp

// Pressure loads on colliders (see pressure_forces.h).
#include "fluid/solids/pressure_forces.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "fluid/grid_index.h"

namespace vp {
namespace {

// A box of cells around the collider with the pressure known or extended into it.
struct LocalPressure {
  Eigen::Vector3i lo, dims;
  Array<double> value;
  Array<int> layer;  // 0 known from the solve, k > 0 extended in layer k, -1 unknown
  Array<uint8_t> air;  // air of a liquid (p = 0, not fluid)

  int64_t index(const Eigen::Vector3i& c) const {
    const Eigen::Vector3i l = c - lo;
    return l.x() + int64_t(dims.x()) * (l.y() + int64_t(dims.y()) * l.z());
  }
  bool contains(const Eigen::Vector3i& c) const {
    return ((c - lo).array() >= 0).all() && ((c - lo).array() < dims.array()).all();
  }
};

// A cell no fluid can reach: every face closed by colliders or walls.
bool solidCell(const MacGrid& grid, const FaceFractionField& fractions, const Eigen::Vector3i& c) {
  for (int a = 0; a < 3; ++a)
    for (int up = 0; up < 2; ++up) {
      Eigen::Vector3i f = c;
      f[a] += up;
      if (effectiveOpenFraction(grid, fractions, a, f.x(), f.y(), f.z()) > 0.0) return false;
    }
  return true;
}

void extendIntoSolid(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                     const double* pressure, LocalPressure& local) {
  const int64_t count = int64_t(local.dims.x()) * local.dims.y() * local.dims.z();
  local.value.assign(static_cast<size_t>(count), 0.0);
  local.layer.assign(static_cast<size_t>(count), 0);
  local.air.assign(static_cast<size_t>(count), 0);
  Array<int64_t> unknown;
  for (int k = 0; k < local.dims.z(); ++k)
    for (int j = 0; j < local.dims.y(); ++j)
      for (int i = 0; i < local.dims.x(); ++i) {
        const Eigen::Vector3i c = local.lo + Eigen::Vector3i(i, j, k);
        const int64_t l = local.index(c);
        const size_t g = grid.cellIndex(c.x(), c.y(), c.z());
        if (op.isFluid(g)) {
          local.value[l] = pressure[g];
        } else if (solidCell(grid, fractions, c)) {
          local.layer[l] = -1;
          unknown.push_back(l);
        } else {
          local.air[l] = 1;  // p = 0
        }
      }
  for (int layer = 1; !unknown.empty(); ++layer) {
    Array<int64_t> still;
    Array<std::pair<int64_t, double>> found;
    for (int64_t l : unknown) {
      const Eigen::Vector3i c = local.lo + Eigen::Vector3i(int(l % local.dims.x()),
                                                          int((l / local.dims.x()) % local.dims.y()),
                                                          int(l / (int64_t(local.dims.x()) * local.dims.y())));
      double sum = 0.0;
      int n = 0;
      for (int a = 0; a < 3; ++a)
        for (int dir = -1; dir <= 1; dir += 2) {
          Eigen::Vector3i nb = c, far = c;
          nb[a] += dir;
          far[a] += 2 * dir;
          if (!local.contains(nb)) continue;
          const int64_t ln = local.index(nb);
          if (local.layer[ln] < 0 || local.layer[ln] >= layer) continue;
          const bool farKnown = local.contains(far) && local.layer[local.index(far)] >= 0 &&
                                local.layer[local.index(far)] < layer;
          sum += farKnown ? 2.0 * local.value[ln] - local.value[local.index(far)] : local.value[ln];
          ++n;
        }
      if (n > 0) found.emplace_back(l, sum / n);
      else still.push_back(l);
    }
    if (found.empty()) break;  // cut off from every known cell: those stay 0
    for (const auto& [l, v] : found) local.value[l] = v, local.layer[l] = layer;
    unknown.swap(still);
  }
}

// The solid part of the face's dual cell (the h^3 box centred on the face), by the midpoint
// rule over 4 slices parallel to the face. The face's own coverage would count a body that
// ends exactly on a grid plane a half cell too long, and jump by a whole cell layer as a
// body crosses grid planes; the slices make the error at most h/8 and the steps a quarter.
double dualCellSolidFraction(const PreparedCollider& collider, AxisFace face) {
  const double base = face.centre[face.axis];
  double sum = 0.0;
  for (int slice = -3; slice <= 3; slice += 2) {
    face.centre[face.axis] = base + slice * face.h / 8.0;
    sum += coveredFraction(collider, face);
  }
  return 0.25 * sum;
}

}  // namespace

PressureLoad pressureLoadOnCollider(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                                    const double* pressure, double density, const PreparedCollider& collider,
                                    const Vec3& centre) {
  PressureLoad load;
  const MacGridSpec& s = grid.spec;
  const Eigen::Vector3i n(s.nx, s.ny, s.nz);
  LocalPressure local;
  Eigen::Vector3i hi;
  for (int a = 0; a < 3; ++a) {
    // Two cells of margin: the extrapolation reads two known cells outside the body.
    const double l = (std::max(collider.bounds.lo[a], s.origin[a] - s.h) - s.origin[a]) / s.h;
    const double u = (std::min(collider.bounds.hi[a], s.origin[a] + (n[a] + 1) * s.h) - s.origin[a]) / s.h;
    local.lo[a] = clampIndex(std::floor(l) - 2.0, 0, n[a]);
    hi[a] = clampIndex(std::ceil(u) + 2.0, -1, n[a] - 1);
    if (local.lo[a] > hi[a]) return load;
  }
  local.dims = hi - local.lo + Eigen::Vector3i::Ones();
  extendIntoSolid(grid, fractions, op, pressure, local);
  const double area = s.h * s.h;
  double wetVolume = 0.0;  // each axis' faces cover the volume once: a third from each
  for (int a = 0; a < 3; ++a)
    for (int k = local.lo.z(); k <= hi.z(); ++k)
      for (int j = local.lo.y(); j <= hi.y(); ++j)
        for (int i = local.lo.x(); i <= hi.x(); ++i) {
          // The low face of cell (i, j, k) along a; the cell below it along a is `low`.
          Eigen::Vector3i high(i, j, k), low(i, j, k);
          low[a] -= 1;
          if (!local.contains(low)) continue;
          if (grid.isWallFace(a, i, j, k)) continue;
          AxisFace face;
          face.axis = a;
          face.h = s.h;
          face.centre = grid.faceCentre(a, i, j, k);
          const double covered = dualCellSolidFraction(collider, face);
          if (!(covered > 0.0)) continue;
          const int64_t lh = local.index(high), ll = local.index(low);
          const double dp = local.value[lh] - local.value[ll];
          if (!local.air[lh] && !local.air[ll]) wetVolume += covered * area * s.h / 3.0;
          Vec3 f = Vec3::Zero();
          f[a] = -covered * area * dp;
          load.force += f;
          load.torque += (face.centre - centre).cross(f);
        }
  load.addedMass = density * wetVolume;
  return load;
}

}  // namespace vp

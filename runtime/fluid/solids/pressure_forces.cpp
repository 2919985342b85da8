// Pressure loads on colliders (see pressure_forces.h).
#include "fluid/solids/pressure_forces.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "fluid/grid_index.h"
#include "fluid/solids/extended_pressure.h"
#include "fluid/surface/hydrostatic_pressure.h"

namespace vp {
namespace {

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

// The sums of pressure_forces.h over the faces `collider` covers within local's box.
PressureLoad loadOverCoveredFaces(const MacGrid& grid, const LocalPressure& local, double density,
                                  const PreparedCollider& collider, const Vec3& centre) {
  PressureLoad load;
  const MacGridSpec& s = grid.spec;
  const Eigen::Vector3i hi = local.lo + local.dims - Eigen::Vector3i::Ones();
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

// Adds `sign` times the hydrostatic pressure under the liquid's surface at each cell centre of
// local's box.
void addHydrostatic(const MacGrid& grid, double density, const LiquidWeight& liquid, double sign,
                    LocalPressure* local) {
  const Eigen::Vector3i hi = local->lo + local->dims - Eigen::Vector3i::Ones();
  const Aabb box{grid.cellCentre(local->lo.x(), local->lo.y(), local->lo.z()),
                 grid.cellCentre(hi.x(), hi.y(), hi.z())};
  const HydrostaticPressure hydrostatic(grid, liquid.liquidPhi, density, liquid.gravity, box);
  for (int k = local->lo.z(); k <= hi.z(); ++k)
    for (int j = local->lo.y(); j <= hi.y(); ++j)
      for (int i = local->lo.x(); i <= hi.x(); ++i)
        local->value[local->index(Eigen::Vector3i(i, j, k))] += sign * hydrostatic.at(grid.cellCentre(i, j, k));
}

}  // namespace

PressureLoad pressureLoadOnCollider(const MacGrid& grid, const FaceFractionField& fractions, const CutCellPoisson& op,
                                    const double* pressure, double density, const PreparedCollider& collider,
                                    const Vec3& centre, const LiquidWeight* less) {
  LocalPressure local;
  if (!localPressureAround(grid, fractions, op, pressure, nullptr, collider.bounds, nullptr, &local))
    return PressureLoad{};
  if (less != nullptr && less->liquidPhi != nullptr) addHydrostatic(grid, density, *less, -1.0, &local);
  return loadOverCoveredFaces(grid, local, density, collider, centre);
}

PressureLoad hydrostaticLoadOnCollider(const MacGrid& grid, const double* liquidPhi, double density,
                                       const Vec3& gravity, const PreparedCollider& collider, const Vec3& centre) {
  LocalPressure local;
  if (liquidPhi == nullptr || !cellBoxAround(grid.spec, collider.bounds, &local)) return PressureLoad{};
  const size_t count = static_cast<size_t>(local.dims.prod());
  local.value.assign(count, 0.0);
  addHydrostatic(grid, density, LiquidWeight{liquidPhi, gravity}, 1.0, &local);
  local.air.resize(count);
  for (size_t c = 0; c < count; ++c) local.air[c] = local.value[c] > 0.0 ? 0 : 1;
  return loadOverCoveredFaces(grid, local, density, collider, centre);
}

}  // namespace vp

// Emitters, drains and initial regions of fluid actors (see fluid_sources.h).
#include "fluid/fluid_sources.h"

#include <algorithm>
#include <cmath>

#include "fluid/grid_index.h"

namespace vp {

double FluidShape::signedDistance(const Vec3& x) const {
  if (type == Type::Sphere) return (x - centre).norm() - radius;
  const Vec3 q = (x - centre).cwiseAbs() - halfExtents;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

namespace {

// Calls visit(i, j, k) for the cells whose centres may lie inside `shape` (its box).
template <class Visit>
void forCellsNear(const MacGrid& grid, const FluidShape& shape, const Visit& visit) {
  const Vec3 extent = shape.type == FluidShape::Type::Sphere ? Vec3::Constant(shape.radius) : shape.halfExtents;
  const MacGridSpec& s = grid.spec;
  const int n[3] = {s.nx, s.ny, s.nz};
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = clampIndex(std::floor((shape.centre[a] - extent[a] - s.origin[a]) / s.h - 0.5), 0, n[a]);
    hi[a] = clampIndex(std::ceil((shape.centre[a] + extent[a] - s.origin[a]) / s.h - 0.5), -1, n[a] - 1);
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) visit(i, j, k);
}

void setFaceVelocitiesInside(MacGrid& grid, const FluidEmitter& e) {
  forCellsNear(grid, e.shape, [&](int i, int j, int k) {
    for (int a = 0; a < 3; ++a) {
      for (int up = 0; up < 2; ++up) {
        Eigen::Vector3i f(i, j, k);
        f[a] += up;
        if (grid.isWallFace(a, f.x(), f.y(), f.z())) continue;
        if (e.shape.signedDistance(grid.faceCentre(a, f.x(), f.y(), f.z())) < 0.0)
          grid.velocity[a][grid.faceIndex(a, f.x(), f.y(), f.z())] = e.velocity[a];
      }
    }
  });
}

}  // namespace

void applySmokeEmitters(MacGrid& grid, const std::vector<FluidEmitter>& emitters, double dt,
                        Array<double>& smokeDensity, Array<double>& temperature) {
  for (const FluidEmitter& e : emitters) {
    if (!e.enabled) continue;
    forCellsNear(grid, e.shape, [&](int i, int j, int k) {
      if (e.shape.signedDistance(grid.cellCentre(i, j, k)) >= 0.0) return;
      const size_t c = grid.cellIndex(i, j, k);
      smokeDensity[c] += e.densityRate * dt;
      temperature[c] = e.temperature;
    });
    setFaceVelocitiesInside(grid, e);
  }
}

void applyLiquidEmitters(MacGrid& grid, const std::vector<FluidEmitter>& emitters, Array<double>& phi) {
  for (const FluidEmitter& e : emitters) {
    if (!e.enabled) continue;
    forCellsNear(grid, e.shape, [&](int i, int j, int k) {
      const size_t c = grid.cellIndex(i, j, k);
      phi[c] = std::min(phi[c], e.shape.signedDistance(grid.cellCentre(i, j, k)));
    });
    setFaceVelocitiesInside(grid, e);
  }
}

void applyDrains(const MacGrid& grid, const std::vector<FluidShape>& drains, Array<double>& phi) {
  for (const FluidShape& d : drains)
    forCellsNear(grid, d, [&](int i, int j, int k) {
      const size_t c = grid.cellIndex(i, j, k);
      phi[c] = std::max(phi[c], -d.signedDistance(grid.cellCentre(i, j, k)));
    });
}

void initialLiquidLevelSet(const MacGrid& grid, const std::vector<FluidShape>& regions, Array<double>& phi) {
  const MacGridSpec& s = grid.spec;
  const double far = s.h * (s.nx + s.ny + s.nz);
  phi.assign(static_cast<size_t>(grid.cellCount()), far);
  for (int k = 0; k < s.nz; ++k)
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) {
        double d = far;
        for (const FluidShape& r : regions) d = std::min(d, r.signedDistance(grid.cellCentre(i, j, k)));
        phi[grid.cellIndex(i, j, k)] = d;
      }
}

}  // namespace vp

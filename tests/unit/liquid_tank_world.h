// Liquid tanks for tests of bodies in a liquid: the tank's definition, a world holding one open
// at the top, and the mean height of its surface away from a body.
#pragma once

#include <cmath>
#include <memory>

#include "fluid/fluid_actor.h"
#include "world.h"
#include "world_test_util.h"

namespace vp {
namespace testutil {

inline FluidDesc liquidTank(int nx, int ny, int nz, double h, double fillHeight) {
  FluidDesc d;
  d.kind = FluidKind::Liquid;
  d.grid.origin = Vec3::Zero();
  d.grid.h = h;
  d.grid.nx = nx, d.grid.ny = ny, d.grid.nz = nz;
  d.density = 1000.0;
  d.solver.pressureTolerance = 1e-8;
  d.solver.pressureMaxIterations = 2000;
  FluidShape water;
  water.type = FluidShape::Type::Box;
  water.halfExtents = Vec3(nx * h, fillHeight / 2, nz * h);
  water.centre = Vec3(nx * h / 2, fillHeight / 2, nz * h / 2);
  d.initialLiquid.push_back(water);
  return d;
}

// Height of the zero level set, averaged over the columns at least `margin` outside the
// box footprint |x - cx|, |z - cz| < half (waves average out over the tank).
inline double meanSurfaceHeight(const FluidActor& f, const Vec3& boxCentre, double half, double margin) {
  const MacGrid& g = f.grid();
  double sum = 0.0;
  int columns = 0;
  for (int k = 0; k < g.spec.nz; ++k)
    for (int i = 0; i < g.spec.nx; ++i) {
      const Vec3 c = g.cellCentre(i, 0, k);
      if (std::abs(c.x() - boxCentre.x()) < half + margin && std::abs(c.z() - boxCentre.z()) < half + margin) continue;
      for (int j = 0; j + 1 < g.spec.ny; ++j) {
        const double a = f.levelSet()[g.cellIndex(i, j, k)], b = f.levelSet()[g.cellIndex(i, j + 1, k)];
        if (a < 0.0 && b >= 0.0) {
          sum += g.cellCentre(i, j, k).y() + g.spec.h * a / (a - b);
          ++columns;
          break;
        }
      }
    }
  return columns > 0 ? sum / columns : 0.0;
}

// A world (no frame budget) holding an n³ tank of 1 m filled to `fill`, open at the top, for
// bodies floating in it; null (and a test failure) if it cannot be made.
inline std::unique_ptr<World> worldWithOpenTank(int n, double fill, double pressureTolerance, FluidHandle* fluid,
                                         double kinematicViscosity = 0.0) {
  std::unique_ptr<World> world = unbudgetedWorld();
  if (!world) return nullptr;
  FluidDesc d = liquidTank(n, n, n, 1.0 / n, fill);
  d.sides[3] = DomainSide::Open;
  d.solver.pressureTolerance = pressureTolerance;
  d.kinematicViscosity = kinematicViscosity;
  const Status created = world->createFluid(d, fluid);
  EXPECT_EQ(created, Status::Ok) << lastError();
  return created == Status::Ok ? std::move(world) : nullptr;
}

}  // namespace testutil
}  // namespace vp

// Shared helpers for the liquid tests: closed tanks, level sets sampled from analytic signed
// distances, face loops, and the net outflow written from its definition.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "collide/face_coverage.h"
#include "fluid/mac_grid.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {
namespace testutil {

constexpr std::array<DomainSide, 6> kClosedTank{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                                DomainSide::Wall, DomainSide::Wall, DomainSide::Wall};

inline MacGridSpec unitCubeGrid(int n) {
  MacGridSpec spec;
  spec.h = 1.0 / n;
  spec.nx = spec.ny = spec.nz = n;
  return spec;
}

// A box tilted about two axes, small enough to sit inside a unit tank around `centre`.
inline ColliderShape tiltedBox(const Eigen::Vector3d& centre) {
  ColliderShape b;
  b.kind = ShapeKind::Box;
  b.halfExtents = Eigen::Vector3d(0.18, 0.08, 0.22);
  b.rotation = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitX());
  b.translation = centre;
  return b;
}

// visit(axis, i, j, k, faceIndex) for every face of every axis.
template <class Visit>
void forEachFace(const MacGrid& grid, const Visit& visit) {
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid.faceDims(a);
    for (int k = 0; k < d.z(); ++k)
      for (int j = 0; j < d.y(); ++j)
        for (int i = 0; i < d.x(); ++i) visit(a, i, j, k, grid.faceIndex(a, i, j, k));
  }
}

// The largest |u| over the faces next to a liquid cell (phi < 0 on either side; a boundary
// face looks at its one cell).
inline double maxLiquidFaceSpeed(const MacGrid& grid, const Array<double>& phi) {
  const int cells[3] = {grid.spec.nx, grid.spec.ny, grid.spec.nz};
  double worst = 0.0;
  forEachFace(grid, [&](int a, int i, int j, int k, size_t face) {
    Eigen::Vector3i low(i, j, k), high(i, j, k);
    low[a] = std::max(low[a] - 1, 0);
    high[a] = std::min(high[a], cells[a] - 1);
    if (phi[grid.cellIndex(low.x(), low.y(), low.z())] >= 0.0 && phi[grid.cellIndex(high.x(), high.y(), high.z())] >= 0.0)
      return;
    worst = std::max(worst, std::abs(grid.velocity[a][face]));
  });
  return worst;
}

// sdf(x) at every cell centre, in cell order.
template <class Sdf>
Array<double> sampleCells(const MacGrid& grid, const Sdf& sdf) {
  Array<double> values(static_cast<size_t>(grid.cellCount()));
  for (int k = 0; k < grid.spec.nz; ++k)
    for (int j = 0; j < grid.spec.ny; ++j)
      for (int i = 0; i < grid.spec.nx; ++i) values[grid.cellIndex(i, j, k)] = sdf(grid.cellCentre(i, j, k));
  return values;
}

// Net outflow of every cell from the definition, not through computeNetOutflow (which also
// builds the right-hand side, so a mistake there would cancel): sum over the cell's faces of
// +-(A_f u_f + (1 - A_f) u_solid,f), + on high faces, raw collider fractions, Wall faces
// carrying only what a collider reaching through them moves ((1 - A_f) u_solid,f).
inline Array<double> netOutflowByDefinition(const MacGrid& grid, const FaceFractionField& fractions) {
  Array<double> out(static_cast<size_t>(grid.cellCount()), 0.0);
  for (int k = 0; k < grid.spec.nz; ++k)
    for (int j = 0; j < grid.spec.ny; ++j)
      for (int i = 0; i < grid.spec.nx; ++i) {
        double sum = 0.0;
        for (int a = 0; a < 3; ++a)
          for (int high = 0; high < 2; ++high) {
            Eigen::Vector3i f(i, j, k);
            f[a] += high;
            const size_t index = grid.faceIndex(a, f.x(), f.y(), f.z());
            const double open = fractions.open[a][index];
            const double fluid = grid.isWallFace(a, f.x(), f.y(), f.z()) ? 0.0 : grid.velocity[a][index];
            const double flux = open * fluid + (1.0 - open) * fractions.solidVelocity[a][index];
            sum += high ? flux : -flux;
          }
        out[grid.cellIndex(i, j, k)] = sum;
      }
  return out;
}

}  // namespace testutil
}  // namespace vp

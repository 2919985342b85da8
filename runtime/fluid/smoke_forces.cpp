// Smoke buoyancy, vorticity confinement and dissipation (see smoke_forces.h).
#include "fluid/smoke_forces.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "gpu_kernels/smoke_force_kernels.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 8;

kernels::CellLattice cellLattice(const MacGridSpec& s) {
  kernels::CellLattice g;
  g.n[0] = s.nx;
  g.n[1] = s.ny;
  g.n[2] = s.nz;
  g.stride[0] = 1;
  g.stride[1] = s.nx;
  g.stride[2] = static_cast<int64_t>(s.nx) * s.ny;
  g.h = s.h;
  return g;
}

// body(i, j, k, cell index) for every cell, rows in parallel.
template <class Body>
void forEachCell(TaskSystem& tasks, const MacGridSpec& s, const Body& body) {
  parallelFor(tasks, static_cast<int64_t>(s.ny) * s.nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int j = static_cast<int>(row % s.ny), k = static_cast<int>(row / s.ny);
      for (int i = 0; i < s.nx; ++i) body(i, j, k, static_cast<int64_t>(i) + s.nx * row);
    }
  });
}

// Adds dt times the mean of the force over each a-face's two cells (the one cell at the
// domain's sides) to the face velocities; cellForce(c) is the force's component a at cell c.
template <class CellForce>
void addCellForceToFaces(TaskSystem& tasks, MacGrid& grid, int a, double dt, const CellForce& cellForce) {
  const MacGridSpec& s = grid.spec;
  const Eigen::Vector3i d = grid.faceDims(a);
  const int64_t nx = s.nx, ny = s.ny, nz = s.nz;
  double* u = grid.velocity[a].data();
  parallelFor(tasks, static_cast<int64_t>(d.y()) * d.z(), kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int64_t j = row % d.y(), k = row / d.y();
      double* faces = u + d.x() * row;
      auto add = [&](int64_t f, int64_t low, int64_t high) {
        faces[f] = kernels::faceVelocityAfterForce(faces[f], dt, cellForce(low), cellForce(high));
      };
      if (a == 0) {
        const int64_t c = nx * (j + ny * k);
        add(0, c, c);
        for (int64_t i = 1; i < nx; ++i) add(i, c + i - 1, c + i);
        add(nx, c + nx - 1, c + nx - 1);
        continue;
      }
      // The rows of cells below and above the face row along a.
      const int64_t at = a == 1 ? j : k, cells = a == 1 ? ny : nz;
      const int64_t below = std::max<int64_t>(at - 1, 0), above = std::min(at, cells - 1);
      const int64_t low = a == 1 ? nx * (below + ny * k) : nx * (j + ny * below);
      const int64_t high = a == 1 ? nx * (above + ny * k) : nx * (j + ny * above);
      for (int64_t i = 0; i < nx; ++i) add(i, low + i, high + i);
    }
  });
}

}  // namespace

void applyBuoyancy(TaskSystem& tasks, MacGrid& grid, const Array<double>& smokeDensity,
                   const Array<double>& temperature, const SmokeParameters& p, const Vec3& gravity,
                   double dt) {
  const double g = gravity.norm();
  if (!(g > 0.0)) return;
  const Vec3 up = -gravity / g;
  const double* density = smokeDensity.data();
  const double* heat = temperature.data();
  for (int a = 0; a < 3; ++a)
    addCellForceToFaces(tasks, grid, a, dt, [&](int64_t c) {
      return kernels::buoyancy(up[a], p.densityBuoyancy, p.thermalBuoyancy, p.ambientTemperature, density[c],
                               heat[c]);
    });
}

// Each cell's velocity and |omega| are read by up to six neighbours' differences: computed once
// per cell in their own passes rather than in every difference.
void applyVorticityConfinement(TaskSystem& tasks, MacGrid& grid, double epsilon, double dt,
                               VorticityWorkspace& work) {
  if (!(epsilon > 0.0)) return;
  const MacGridSpec& s = grid.spec;
  const size_t cells = static_cast<size_t>(grid.cellCount());
  work.omega.resize(3 * cells);
  work.omegaNorm.resize(cells);
  work.force.resize(3 * cells);
  const kernels::CellLattice lattice = cellLattice(s);
  const double* faces[3] = {grid.velocity[0].data(), grid.velocity[1].data(), grid.velocity[2].data()};
  double* velocity = work.force.data();
  double* omega = work.omega.data();
  double* omegaNorm = work.omegaNorm.data();
  forEachCell(tasks, s, [&](int i, int j, int k, int64_t c) {
    kernels::cellVelocityAt(faces, s.nx, s.ny, i, j, k, velocity + 3 * c);
  });
  forEachCell(tasks, s, [&](int i, int j, int k, int64_t c) {
    kernels::vorticityAt(lattice, velocity, i, j, k, omega + 3 * c);
    omegaNorm[c] = kernels::norm3(omega + 3 * c);
  });
  forEachCell(tasks, s, [&](int i, int j, int k, int64_t c) {
    kernels::confinementAt(lattice, omega, omegaNorm, epsilon, i, j, k, work.force.data() + 3 * c);
  });
  const double* force = work.force.data();
  for (int a = 0; a < 3; ++a) addCellForceToFaces(tasks, grid, a, dt, [&](int64_t c) { return force[3 * c + a]; });
}

void dissipate(Array<double>& values, double rate, double dt) {
  if (!(rate > 0.0)) return;
  const double factor = std::exp(-rate * dt);
  for (double& v : values) v *= factor;
}

}  // namespace vp

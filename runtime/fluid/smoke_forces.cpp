// Smoke buoyancy, vorticity confinement and dissipation (see smoke_forces.h).
#include "fluid/smoke_forces.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "fluid/cell_lattice.h"
#include "gpu_kernels/smoke_force_kernels.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 8;
constexpr int64_t kValueGrain = 4096;

// body(i, j, k, cell index) for every cell: a pass over cell rows.
template <class Body>
void addCellPass(SlabPasses& passes, const MacGridSpec& s, Body body) {
  passes.addParallel(static_cast<int64_t>(s.ny) * s.nz, s.nx, kRowGrain, [s, body](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int j = static_cast<int>(row % s.ny), k = static_cast<int>(row / s.ny);
      for (int i = 0; i < s.nx; ++i) body(i, j, k, static_cast<int64_t>(i) + s.nx * row);
    }
  });
}

// addCellPass, but cells with neighbours on both sides along every axis get interior(c)
// instead: the runs of them inside a row are loops without the boundary clamps.
template <class Body, class Interior>
void addCellPassWithInterior(SlabPasses& passes, const MacGridSpec& s, Body body, Interior interior) {
  passes.addParallel(static_cast<int64_t>(s.ny) * s.nz, s.nx, kRowGrain,
                     [s, body, interior](int64_t begin, int64_t end) {
                       for (int64_t row = begin; row < end; ++row) {
                         const int j = static_cast<int>(row % s.ny), k = static_cast<int>(row / s.ny);
                         const int64_t c0 = s.nx * row;
                         if (j == 0 || j + 1 == s.ny || k == 0 || k + 1 == s.nz || s.nx < 3) {
                           for (int i = 0; i < s.nx; ++i) body(i, j, k, c0 + i);
                           continue;
                         }
                         body(0, j, k, c0);
                         for (int64_t c = c0 + 1; c + 1 < c0 + s.nx; ++c) interior(c);
                         body(s.nx - 1, j, k, c0 + s.nx - 1);
                       }
                     });
}

// Adds dt times the mean of the force over each a-face's two cells (the one cell at the
// domain's sides) to the face velocities; cellForce(c) is the force's component a at cell c.
// A pass over the a-faces' rows.
template <class CellForce>
void addCellForceToFaces(SlabPasses& passes, MacGrid& grid, int a, double dt, CellForce cellForce) {
  const Eigen::Vector3i d = grid.faceDims(a);
  MacGrid* g = &grid;
  passes.addParallel(static_cast<int64_t>(d.y()) * d.z(), d.x(), kRowGrain, [g, a, d, dt, cellForce](int64_t begin,
                                                                                                     int64_t end) {
    const MacGridSpec& s = g->spec;
    const int64_t nx = s.nx, ny = s.ny, nz = s.nz;
    double* u = g->velocity[a].data();
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

void addBuoyancyPasses(SlabPasses& passes, MacGrid& grid, const Array<double>& smokeDensity,
                       const Array<double>& temperature, const SmokeParameters& p, const Vec3& gravity, double dt) {
  const double g = gravity.norm();
  if (!(g > 0.0)) return;
  const Vec3 up = -gravity / g;
  const Array<double>* density = &smokeDensity;
  const Array<double>* heat = &temperature;
  for (int a = 0; a < 3; ++a)
    addCellForceToFaces(passes, grid, a, dt, [density, heat, p, lift = up[a]](int64_t c) {
      return kernels::buoyancy(lift, p.densityBuoyancy, p.thermalBuoyancy, p.ambientTemperature, (*density)[c],
                               (*heat)[c]);
    });
}

// Each cell's velocity and |omega| are read by up to six neighbours' differences: computed once
// per cell in their own passes rather than in every difference.
void addVorticityConfinementPasses(SlabPasses& passes, MacGrid& grid, double epsilon, double dt,
                                   VorticityWorkspace& work) {
  if (!(epsilon > 0.0)) return;
  const MacGridSpec& s = grid.spec;
  const size_t cells = static_cast<size_t>(grid.cellCount());
  work.omega.resize(3 * cells);
  work.omegaNorm.resize(cells);
  work.force.resize(3 * cells);
  const kernels::CellLattice lattice = cellLattice(s);
  MacGrid* g = &grid;
  VorticityWorkspace* w = &work;
  addCellPass(passes, s, [g, w](int i, int j, int k, int64_t c) {
    const MacGridSpec& spec = g->spec;
    const double* faces[3] = {g->velocity[0].data(), g->velocity[1].data(), g->velocity[2].data()};
    kernels::cellVelocityAt(faces, spec.nx, spec.ny, i, j, k, w->force.data() + 3 * c);
  });
  const double twoH = 2.0 * s.h;  // the central differences' span inside the grid
  addCellPassWithInterior(
      passes, s,
      [lattice, w](int i, int j, int k, int64_t c) {
        kernels::vorticityAt(lattice, w->force.data(), i, j, k, w->omega.data() + 3 * c);
        w->omegaNorm[static_cast<size_t>(c)] = kernels::norm3(w->omega.data() + 3 * c);
      },
      [lattice, w, twoH](int64_t c) {
        kernels::interiorVorticityAt(lattice, w->force.data(), c, twoH, w->omega.data() + 3 * c);
        w->omegaNorm[static_cast<size_t>(c)] = kernels::norm3(w->omega.data() + 3 * c);
      });
  addCellPassWithInterior(
      passes, s,
      [lattice, w, epsilon](int i, int j, int k, int64_t c) {
        kernels::confinementAt(lattice, w->omega.data(), w->omegaNorm.data(), epsilon, i, j, k,
                               w->force.data() + 3 * c);
      },
      [lattice, w, epsilon, twoH](int64_t c) {
        kernels::interiorConfinementAt(lattice, w->omega.data(), w->omegaNorm.data(), epsilon, c, twoH,
                                       w->force.data() + 3 * c);
      });
  for (int a = 0; a < 3; ++a)
    addCellForceToFaces(passes, grid, a, dt, [w, a](int64_t c) { return w->force[static_cast<size_t>(3 * c + a)]; });
}

// values *= exp(-rate dt), a pass over the values.
void addDissipationPass(SlabPasses& passes, Array<double>& values, double rate, double dt) {
  if (!(rate > 0.0)) return;
  const double factor = std::exp(-rate * dt);
  Array<double>* v = &values;
  passes.addParallel(static_cast<int64_t>(values.size()), 1, kValueGrain, [v, factor](int64_t begin, int64_t end) {
    double* x = v->data();
    for (int64_t c = begin; c < end; ++c) x[c] *= factor;
  });
}

}  // namespace

void addSmokeForcePasses(SlabPasses& passes, MacGrid& grid, Array<double>& smokeDensity, Array<double>& temperature,
                         const SmokeParameters& params, const Vec3& gravity, double dt, VorticityWorkspace& work) {
  addBuoyancyPasses(passes, grid, smokeDensity, temperature, params, gravity, dt);
  addVorticityConfinementPasses(passes, grid, params.vorticityConfinement, dt, work);
  addDissipationPass(passes, smokeDensity, params.densityDissipation, dt);
  addDissipationPass(passes, temperature, params.temperatureDissipation, dt);
}

void addGravityPasses(SlabPasses& passes, MacGrid& grid, const Vec3& gravity, double dt) {
  MacGrid* g = &grid;
  for (int a = 0; a < 3; ++a) {
    if (gravity[a] == 0.0) continue;
    const Eigen::Vector3i d = grid.faceDims(a);
    const double dv = dt * gravity[a];
    passes.addParallel(static_cast<int64_t>(d.y()) * d.z(), d.x(), kRowGrain, [g, a, d, dv](int64_t begin, int64_t end) {
      double* u = g->velocity[a].data();
      for (int64_t f = begin * d.x(); f < end * d.x(); ++f) u[f] += dv;
    });
  }
}

}  // namespace vp

// Smoke buoyancy, vorticity confinement and dissipation (see smoke_forces.h).
#include "fluid/smoke_forces.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"

namespace vp {
namespace {

constexpr int64_t kRowGrain = 8;

int cellsAlong(const MacGridSpec& s, int a) { return a == 0 ? s.nx : a == 1 ? s.ny : s.nz; }

// Adds dt * (mean of cellValue over the face's two cells, one at the domain boundary) to
// every face velocity of every axis; cellValue(cell, axis) gives the force component.
template <class CellForce>
void addCellForceToFaces(TaskSystem& tasks, MacGrid& grid, double dt, const CellForce& cellForce) {
  const MacGridSpec& s = grid.spec;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i d = grid.faceDims(a);
    std::vector<double>& u = grid.velocity[a];
    parallelFor(tasks, static_cast<int64_t>(d.y()) * d.z(), kRowGrain, [&](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) {
        const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
        for (int i = 0; i < d.x(); ++i) {
          Eigen::Vector3i hi(i, j, k), lo(i, j, k);
          lo[a] -= 1;
          hi[a] = std::min(hi[a], cellsAlong(s, a) - 1);
          lo[a] = std::max(lo[a], 0);
          const double f = 0.5 * (cellForce(grid.cellIndex(lo.x(), lo.y(), lo.z()), a) +
                                  cellForce(grid.cellIndex(hi.x(), hi.y(), hi.z()), a));
          u[grid.faceIndex(a, i, j, k)] += dt * f;
        }
      }
    });
  }
}

}  // namespace

void applyBuoyancy(TaskSystem& tasks, MacGrid& grid, const std::vector<double>& smokeDensity,
                   const std::vector<double>& temperature, const SmokeParameters& p, const Vec3& gravity,
                   double dt) {
  const double g = gravity.norm();
  if (!(g > 0.0)) return;
  const Vec3 up = -gravity / g;
  addCellForceToFaces(tasks, grid, dt, [&](size_t c, int a) {
    return up[a] * (-p.densityBuoyancy * smokeDensity[c] +
                    p.thermalBuoyancy * (temperature[c] - p.ambientTemperature));
  });
}

void applyVorticityConfinement(TaskSystem& tasks, MacGrid& grid, double epsilon, double dt,
                               VorticityWorkspace& work) {
  if (!(epsilon > 0.0)) return;
  const MacGridSpec& s = grid.spec;
  const size_t cells = static_cast<size_t>(grid.cellCount());
  work.omega.resize(cells);
  work.force.resize(cells);
  const Eigen::Vector3i n(s.nx, s.ny, s.nz);
  // One-sided at the domain boundary: central differences over the clamped neighbours.
  auto neighbours = [&](int i, int j, int k, int a, Eigen::Vector3i* lo, Eigen::Vector3i* hi) {
    *lo = Eigen::Vector3i(i, j, k);
    *hi = *lo;
    (*lo)[a] = std::max((*lo)[a] - 1, 0);
    (*hi)[a] = std::min((*hi)[a] + 1, n[a] - 1);
    return static_cast<double>((*hi)[a] - (*lo)[a]) * s.h;
  };
  parallelFor(tasks, static_cast<int64_t>(s.ny) * s.nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int j = static_cast<int>(row % s.ny), k = static_cast<int>(row / s.ny);
      for (int i = 0; i < s.nx; ++i) {
        Eigen::Matrix3d gradient;  // gradient(c, a) = d u_c / d x_a
        for (int a = 0; a < 3; ++a) {
          Eigen::Vector3i lo, hi;
          const double span = neighbours(i, j, k, a, &lo, &hi);
          gradient.col(a) = span > 0.0 ? Eigen::Vector3d((grid.cellVelocity(hi.x(), hi.y(), hi.z()) -
                                                           grid.cellVelocity(lo.x(), lo.y(), lo.z())) / span)
                                       : Eigen::Vector3d::Zero();
        }
        work.omega[grid.cellIndex(i, j, k)] = Eigen::Vector3d(gradient(2, 1) - gradient(1, 2),
                                                              gradient(0, 2) - gradient(2, 0),
                                                              gradient(1, 0) - gradient(0, 1));
      }
    }
  });
  parallelFor(tasks, static_cast<int64_t>(s.ny) * s.nz, kRowGrain, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row < end; ++row) {
      const int j = static_cast<int>(row % s.ny), k = static_cast<int>(row / s.ny);
      for (int i = 0; i < s.nx; ++i) {
        Eigen::Vector3d eta;
        for (int a = 0; a < 3; ++a) {
          Eigen::Vector3i lo, hi;
          const double span = neighbours(i, j, k, a, &lo, &hi);
          eta[a] = span > 0.0 ? (work.omega[grid.cellIndex(hi.x(), hi.y(), hi.z())].norm() -
                                 work.omega[grid.cellIndex(lo.x(), lo.y(), lo.z())].norm()) / span
                              : 0.0;
        }
        const size_t c = grid.cellIndex(i, j, k);
        // The small constant keeps N finite where |omega| is flat; such places get no force.
        const Eigen::Vector3d normal = eta / (eta.norm() + 1e-12 / s.h);
        work.force[c] = epsilon * s.h * normal.cross(work.omega[c]);
      }
    }
  });
  addCellForceToFaces(tasks, grid, dt, [&](size_t c, int a) { return work.force[c][a]; });
}

void dissipate(std::vector<double>& values, double rate, double dt) {
  if (!(rate > 0.0)) return;
  const double factor = std::exp(-rate * dt);
  for (double& v : values) v *= factor;
}

}  // namespace vp

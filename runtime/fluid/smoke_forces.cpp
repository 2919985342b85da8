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

// Each cell's velocity and |omega| are read by up to six neighbours' differences: computed once
// per cell in their own passes rather than in every difference.
void applyVorticityConfinement(TaskSystem& tasks, MacGrid& grid, double epsilon, double dt,
                               VorticityWorkspace& work) {
  if (!(epsilon > 0.0)) return;
  const MacGridSpec& s = grid.spec;
  const size_t cells = static_cast<size_t>(grid.cellCount());
  work.omega.resize(cells);
  work.omegaNorm.resize(cells);
  work.force.resize(cells);
  const Eigen::Vector3i n(s.nx, s.ny, s.nz);
  const int64_t stride[3] = {1, s.nx, static_cast<int64_t>(s.nx) * s.ny};
  // One-sided at the domain boundary: central differences over the clamped neighbours. Gives
  // the offsets of the two cells and the distance between them (0 with one cell along a).
  auto neighbours = [&](int i, int j, int k, int a, int64_t* lo, int64_t* hi) {
    const int at = a == 0 ? i : a == 1 ? j : k;
    const int below = std::max(at - 1, 0), above = std::min(at + 1, n[a] - 1);
    *lo = (below - at) * stride[a];
    *hi = (above - at) * stride[a];
    return static_cast<double>(above - below) * s.h;
  };
  auto forEachCell = [&](const auto& body) {
    parallelFor(tasks, static_cast<int64_t>(s.ny) * s.nz, kRowGrain, [&](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) {
        const int j = static_cast<int>(row % s.ny), k = static_cast<int>(row / s.ny);
        for (int i = 0; i < s.nx; ++i) body(i, j, k, static_cast<int64_t>(i) + s.nx * row);
      }
    });
  };
  std::vector<Eigen::Vector3d>& velocity = work.force;
  forEachCell([&](int i, int j, int k, int64_t c) { velocity[c] = grid.cellVelocity(i, j, k); });
  forEachCell([&](int i, int j, int k, int64_t c) {
    Eigen::Matrix3d gradient;  // gradient(c, a) = d u_c / d x_a
    for (int a = 0; a < 3; ++a) {
      int64_t lo, hi;
      const double span = neighbours(i, j, k, a, &lo, &hi);
      gradient.col(a) =
          span > 0.0 ? Eigen::Vector3d((velocity[c + hi] - velocity[c + lo]) / span) : Eigen::Vector3d::Zero();
    }
    work.omega[c] = Eigen::Vector3d(gradient(2, 1) - gradient(1, 2), gradient(0, 2) - gradient(2, 0),
                                    gradient(1, 0) - gradient(0, 1));
    work.omegaNorm[c] = work.omega[c].norm();
  });
  forEachCell([&](int i, int j, int k, int64_t c) {
    Eigen::Vector3d eta;
    for (int a = 0; a < 3; ++a) {
      int64_t lo, hi;
      const double span = neighbours(i, j, k, a, &lo, &hi);
      eta[a] = span > 0.0 ? (work.omegaNorm[c + hi] - work.omegaNorm[c + lo]) / span : 0.0;
    }
    // The small constant keeps N finite where |omega| is flat; such places get no force.
    const Eigen::Vector3d normal = eta / (eta.norm() + 1e-12 / s.h);
    work.force[c] = epsilon * s.h * normal.cross(work.omega[c]);
  });
  addCellForceToFaces(tasks, grid, dt, [&](size_t c, int a) { return work.force[c][a]; });
}

void dissipate(std::vector<double>& values, double rate, double dt) {
  if (!(rate > 0.0)) return;
  const double factor = std::exp(-rate * dt);
  for (double& v : values) v *= factor;
}

}  // namespace vp

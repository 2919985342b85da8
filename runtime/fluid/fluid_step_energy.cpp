#include "fluid/fluid_step_energy.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"

namespace vp {

namespace {

// A face with a liquid cell on either side.
bool besideLiquid(const MacGrid& grid, const double* phi, int axis, int i, int j, int k) {
  int at[3] = {i, j, k};
  const int cells[3] = {grid.spec.nx, grid.spec.ny, grid.spec.nz};
  if (at[axis] < cells[axis] && phi[grid.cellIndex(at[0], at[1], at[2])] < 0.0) return true;
  --at[axis];
  return at[axis] >= 0 && phi[grid.cellIndex(at[0], at[1], at[2])] < 0.0;
}

}  // namespace

double fluidKineticEnergy(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                          const double* liquidPhi, double density) {
  double sum = 0.0;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3i dims = grid.faceDims(a);
    const double* u = grid.velocity[a].data();
    const double* open = fractions.open[a].data();
    const int64_t rows = static_cast<int64_t>(dims.y()) * dims.z();
    sum += parallelReduce<double>(tasks, rows, 64, [&](int64_t begin, int64_t end) {
      double s = 0.0;
      for (int64_t row = begin; row < end; ++row) {
        const int j = static_cast<int>(row % dims.y()), k = static_cast<int>(row / dims.y());
        const size_t first = grid.faceIndex(a, 0, j, k);
        for (int i = 0; i < dims.x(); ++i) {
          if (liquidPhi != nullptr && !besideLiquid(grid, liquidPhi, a, i, j, k)) continue;
          const double v = u[first + i];
          s += open[first + i] * v * v;
        }
      }
      return s;
    });
  }
  const double h = grid.spec.h;
  return 0.5 * density * h * h * h * sum;
}

double largestDeviation(TaskSystem& tasks, const Array<double>& values, double from) {
  struct Max {
    double v = 0.0;
    Max& operator+=(const Max& o) {
      v = std::max(v, o.v);
      return *this;
    }
  };
  return parallelReduce<Max>(tasks, static_cast<int64_t>(values.size()), 1 << 15, [&](int64_t b, int64_t e) {
           Max m;
           for (int64_t c = b; c < e; ++c) {
             const double d = std::abs(values[static_cast<size_t>(c)] - from);
             if (!(d <= m.v)) m.v = std::isnan(d) ? HUGE_VAL : d;
           }
           return m;
         }).v;
}

double fluidSourceWorkBound(double kineticStart, double mass, double acceleration, double boundarySpeed, double dt) {
  const double start = std::sqrt(std::max(kineticStart, 0.0));
  const double added = std::sqrt(0.5 * mass) * (acceleration * dt + boundarySpeed);
  return (start + added) * (start + added) - std::max(kineticStart, 0.0);
}

double smokeAccelerationBound(const SmokeParameters& smoke, double gravity, double densityMax, double heatMax,
                              double speed) {
  // Buoyancy acts only along gravity (none without it); the confinement bound is the header's.
  const double buoyancy =
      gravity > 0.0 ? std::abs(smoke.densityBuoyancy) * densityMax + std::abs(smoke.thermalBuoyancy) * heatMax : 0.0;
  return buoyancy + 4.0 * std::sqrt(3.0) * std::abs(smoke.vorticityConfinement) * speed;
}

}  // namespace vp

#include "fluid/fluid_step_energy.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"

namespace vp {

namespace {

// Σ open u² over one row of faces along x (axis a's faces (·, j, k)); with a level set, over the
// faces beside a liquid cell: the cells below and above each face, rows of phi or null where
// the face is on the domain's side (for x faces the cells are the row's own, one apart).
double rowSum(const double* u, const double* open, int count, const double* phiLow, const double* phiHigh,
              bool alongRow) {
  double s = 0.0;
  if (phiLow == nullptr && phiHigh == nullptr && !alongRow) {
    for (int i = 0; i < count; ++i) s += open[i] * u[i] * u[i];
    return s;
  }
  for (int i = 0; i < count; ++i) {
    bool liquid;
    if (alongRow)  // x faces: cells i - 1 and i of the row phiHigh
      liquid = (i > 0 && phiHigh[i - 1] < 0.0) || (i + 1 < count && phiHigh[i] < 0.0);
    else
      liquid = (phiLow != nullptr && phiLow[i] < 0.0) || (phiHigh != nullptr && phiHigh[i] < 0.0);
    s += liquid ? open[i] * u[i] * u[i] : 0.0;
  }
  return s;
}

}  // namespace

double fluidKineticEnergy(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                          const double* liquidPhi, double density) {
  const MacGridSpec& g = grid.spec;
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
        const double *low = nullptr, *high = nullptr;
        if (liquidPhi != nullptr) {
          const int cell[3] = {0, j, k};
          const int n[3] = {g.nx, g.ny, g.nz};
          if (a == 0 || cell[a] < n[a]) high = liquidPhi + grid.cellIndex(0, j, k);
          if (a != 0 && cell[a] > 0) low = liquidPhi + grid.cellIndex(0, j - (a == 1), k - (a == 2));
        }
        s += rowSum(u + first, open + first, dims.x(), low, high, liquidPhi != nullptr && a == 0);
      }
      return s;
    });
  }
  const double h = g.h;
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

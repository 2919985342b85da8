// Narrow-band redistancing: a plane is reproduced exactly, an exact sphere distance barely
// changes, and a distorted field becomes a distance with its surface where it was.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "fluid/cell_lattice.h"
#include "fluid/surface/free_surface.h"
#include "fluid/surface/level_set_redistance.h"
#include "fluid_liquid_test_util.h"
#include "gpu_kernels/level_set_kernels.h"

namespace vp {
namespace {

struct Field {
  MacGrid grid;
  Array<double> phi, exact;
};

template <class Sdf, class Distort>
Field makeField(int n, const Sdf& sdf, const Distort& distort) {
  Field f;
  EXPECT_EQ(initMacGrid(testutil::unitCubeGrid(n), testutil::kClosedTank, &f.grid), Status::Ok);
  f.exact = testutil::sampleCells(f.grid, sdf);
  f.phi = testutil::sampleCells(f.grid, [&](const Eigen::Vector3d& x) { return distort(x, sdf(x)); });
  return f;
}

RedistanceStats redistance(Field& f, const RedistanceSettings& settings) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  RedistanceWorkspace ws;
  RedistanceStats stats;
  EXPECT_EQ(redistanceLevelSet(*tasks, f.grid.spec, f.phi.data(), settings, ws, &stats), Status::Ok) << lastError();
  EXPECT_TRUE(stats.converged);
  return stats;
}

struct Errors {
  double surfaceCells = 0.0;   // max |phi - exact| on cells next to the sign change
  double band = 0.0;           // max |phi - exact| where |exact| < W h - h, off the sides
  double crossing = 0.0;       // max distance of phi's edge crossings from the exact surface
  int64_t signFlips = 0;
};

// crossingError(x) = |exact distance| at a point on the surface of phi.
template <class Sdf>
Errors measure(const Field& f, double bandWidth, const Sdf& sdf) {
  Errors e;
  const MacGrid& g = f.grid;
  const int n = g.spec.nx;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const size_t c = g.cellIndex(i, j, k);
        const double error = std::fabs(f.phi[c] - f.exact[c]);
        if (isLiquid(f.phi[c]) != isLiquid(f.exact[c])) ++e.signFlips;
        // Near the domain's sides a cell's closest surface point may lie outside the grid,
        // where there are no surface cells to propagate from; the upwind scheme's domain of
        // dependence is a cone, so twice the band keeps clear of that.
        const int margin = 2 * static_cast<int>(std::ceil(bandWidth / g.spec.h)) + 1;
        const bool interior = std::min({i, j, k}) >= margin && std::max({i, j, k}) < n - margin;
        if (interior && std::fabs(f.exact[c]) < bandWidth - g.spec.h) e.band = std::max(e.band, error);
        for (int a = 0; a < 3; ++a) {
          Eigen::Vector3i nb(i, j, k);
          nb[a] += 1;
          if (nb[a] >= n) continue;
          const size_t m = g.cellIndex(nb.x(), nb.y(), nb.z());
          if (isLiquid(f.phi[c]) == isLiquid(f.phi[m])) continue;
          e.surfaceCells = std::max({e.surfaceCells, error, std::fabs(f.phi[m] - f.exact[m])});
          const double t = f.phi[c] / (f.phi[c] - f.phi[m]);
          const Eigen::Vector3d x = g.cellCentre(i, j, k) + t * (g.cellCentre(nb.x(), nb.y(), nb.z()) - g.cellCentre(i, j, k));
          e.crossing = std::max(e.crossing, std::fabs(sdf(x)));
        }
      }
  return e;
}

TEST(FluidRedistance, TiltedPlaneIsReproducedExactly) {
  const Eigen::Vector3d normal = Eigen::Vector3d(0.3, 1.0, -0.45).normalized();
  auto sdf = [&](const Eigen::Vector3d& x) { return normal.dot(x - Eigen::Vector3d(0.5, 0.52, 0.5)); };
  // Stretched by 2.5: the subcell initialization divides it out exactly (linear phi).
  Field f = makeField(24, sdf, [](const Eigen::Vector3d&, double d) { return 2.5 * d; });
  RedistanceSettings settings;
  settings.tolerance = 1e-14;
  const RedistanceStats stats = redistance(f, settings);
  const Errors e = measure(f, settings.bandCells * f.grid.spec.h, sdf);
  std::printf("    %lld surface, %lld band cells, %d sweeps; max error surface %.2e h, band %.2e h\n",
              static_cast<long long>(stats.surfaceCells), static_cast<long long>(stats.bandCells), stats.sweeps,
              e.surfaceCells / f.grid.spec.h, e.band / f.grid.spec.h);
  // The Godunov update is exact for a linear distance: what remains is round-off.
  EXPECT_LT(e.band, 1e-12);
  EXPECT_EQ(e.signFlips, 0);
}

const Eigen::Vector3d kCentre(0.503, 0.488, 0.51);
double sphere(const Eigen::Vector3d& x) { return (x - kCentre).norm() - 0.3; }

TEST(FluidRedistance, ExactSphereDistanceBarelyChanges) {
  Field f = makeField(64, sphere, [](const Eigen::Vector3d&, double d) { return d; });
  const RedistanceSettings settings;
  const double h = f.grid.spec.h;
  const RedistanceStats stats = redistance(f, settings);
  const Errors e = measure(f, settings.bandCells * h, sphere);
  std::printf("    %lld surface, %lld band cells, %d sweeps; max error surface cells %.2e h, band %.2e h, "
              "surface moved %.2e h\n",
              static_cast<long long>(stats.surfaceCells), static_cast<long long>(stats.bandCells), stats.sweeps,
              e.surfaceCells / h, e.band / h, e.crossing / h);
  // Surface cells: central differences of a distance to a sphere of radius R (19 h here) give
  // |grad| to O((h / R)^2) relative, times |d| <= h: ~1e-3 h.
  EXPECT_LT(e.surfaceCells, 5e-3 * h);
  // Band: the first-order upwind scheme's error on a curved front grows with the distance
  // travelled, about h^2 / R per cell for a sphere: 4 cells -> 0.2 h at most; measured lower.
  EXPECT_LT(e.band, 0.1 * h);
  EXPECT_EQ(e.signFlips, 0);
  EXPECT_LT(e.crossing, 0.01 * h);
}

TEST(FluidRedistance, DistortedSphereBecomesADistanceWithTheSurfaceKept) {
  // phi * f with f from 0.5 to about 2.5 across the domain: |grad phi| far from 1, zero set
  // unchanged.
  auto distort = [](const Eigen::Vector3d& x, double d) {
    return d * (0.5 + 4.0 * (x.x() - 0.2) * (x.x() - 0.2) + x.y());
  };
  Field f = makeField(64, sphere, distort);
  const RedistanceSettings settings;
  const double h = f.grid.spec.h;
  const Errors before = measure(f, settings.bandCells * h, sphere);
  const RedistanceStats stats = redistance(f, settings);
  const Errors e = measure(f, settings.bandCells * h, sphere);
  std::printf("    before: band error %.2f h; after: %d sweeps, max error surface cells %.2e h, band %.2e h, "
              "surface moved %.2e h (before %.2e h)\n",
              before.band / h, stats.sweeps, e.surfaceCells / h, e.band / h, e.crossing / h, before.crossing / h);
  EXPECT_GT(before.band, h);  // really distorted
  EXPECT_LT(e.crossing, 0.1 * h);
  EXPECT_LT(e.band, 0.15 * h);
  EXPECT_EQ(e.signFlips, 0);
}

// The sweeps stop once no value under the clamp drops by more than the tolerance; values at
// or above it still moving cannot change the result. A block and a drop apart (between them,
// cells reached from both fronts at distances over the clamp that keep falling), against a
// reference with three times the band, swept to round-off: under the default clamp both are
// the same eikonal solution (a value depends only on smaller ones, all in both bands), so the
// default run's result is the reference's clamped, within a few tolerances (the drops shrink
// by more than tenfold per sweep near convergence).
TEST(FluidRedistance, StoppingUnderTheClampGivesTheConvergedResult) {
  auto blockAndDrop = [](const Eigen::Vector3d& x) {
    const Eigen::Vector3d high(0.4, 0.6, 1.0);
    const double block = (x - high).cwiseMax(0.0).norm() + std::min((x - high).maxCoeff(), 0.0);
    return std::min(block, (x - Eigen::Vector3d(0.7, 0.7, 0.5)).norm() - 0.12);
  };
  auto distort = [](const Eigen::Vector3d& x, double d) { return d * (0.6 + x.y()); };
  Field byDefault = makeField(64, blockAndDrop, distort), reference = byDefault;
  const RedistanceSettings settings;
  RedistanceSettings wide;
  wide.bandCells = 3.0 * settings.bandCells;
  wide.tolerance = 1e-15;
  wide.maxSweeps = 1000;
  const RedistanceStats stats = redistance(byDefault, settings);
  redistance(reference, wide);
  const double h = byDefault.grid.spec.h, clamp = settings.bandCells * h;
  double difference = 0.0;
  for (size_t c = 0; c < byDefault.phi.size(); ++c)
    difference = std::max(difference, std::fabs(byDefault.phi[c] - std::copysign(std::min(std::fabs(reference.phi[c]), clamp), reference.phi[c])));
  std::printf("    %d sweeps, largest difference from the wide band's clamped %.2e h\n", stats.sweeps, difference / h);
  EXPECT_LT(difference, 10.0 * settings.tolerance * h);
}

// The sweeps skip cells none of whose neighbours changed since their last update
// (redistanceSweepStaleCell). Against every cell updated in every half-sweep
// (redistanceSweepCell), from the same start (surface cells of a distorted sphere set, the
// rest unreached): the same distances, bit for bit, and the same largest drop, half-sweep by
// half-sweep, until nothing changes. A skipped cell that should have moved breaks both.
TEST(FluidRedistance, SkippingUnchangedNeighbourhoodsGivesTheFullSweepsBits) {
  const Field f = makeField(32, sphere, [](const Eigen::Vector3d& x, double d) { return d * (0.5 + x.x()); });
  const kernels::CellLattice lattice = cellLattice(f.grid.spec);
  const int n = f.grid.spec.nx;
  const double clamp = 4.0 * f.grid.spec.h;
  Array<double> full(f.phi.size(), kernels::unreachedDistance());
  Array<uint8_t> stale(f.phi.size(), 0);
  std::vector<int64_t> byColour[2];
  int64_t surfaceCells = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int64_t c = f.grid.cellIndex(i, j, k);
        bool surface = false;
        const int at[3] = {i, j, k};
        for (int a = 0; a < 3; ++a)
          for (int side = -1; side <= 1; side += 2) {
            int nb[3] = {at[0], at[1], at[2]};
            nb[a] += side;
            if (nb[a] < 0 || nb[a] >= n) continue;
            surface = surface || isLiquid(f.phi[f.grid.cellIndex(nb[0], nb[1], nb[2])]) != isLiquid(f.phi[c]);
          }
        if (surface) {
          full[c] = std::fabs(f.phi[c]);
          ++surfaceCells;
        } else {
          byColour[(i + j + k) & 1].push_back(c);
        }
      }
  ASSERT_GT(surfaceCells, 0);
  // Before the first half-sweep only a surface cell has a distance: its neighbours are stale.
  for (int colour = 0; colour < 2; ++colour)
    for (int64_t c : byColour[colour]) {
      int64_t ijk[3];
      lattice.coordinates(c, ijk);
      for (int a = 0; a < 3; ++a)
        for (int side = -1; side <= 1; side += 2) {
          const int64_t m = ijk[a] + side;
          if (m >= 0 && m < n && full[c + side * lattice.stride[a]] != kernels::unreachedDistance()) stale[c] = 1;
        }
    }
  Array<double> skipping = full;
  int halfSweeps = 0;
  int64_t skipped = 0, updates = 0;
  for (bool changed = true; changed; ++halfSweeps) {
    ASSERT_LT(halfSweeps, 200);
    const Array<double> before = full;
    double dropFull = 0.0, dropSkipping = 0.0;
    updates += static_cast<int64_t>(byColour[halfSweeps & 1].size());
    for (int64_t c : byColour[halfSweeps & 1]) {
      dropFull = std::max(dropFull, kernels::redistanceSweepCell(lattice, c, clamp, full.data()));
      skipped += stale[c] == 0;
      dropSkipping = std::max(dropSkipping,
                              kernels::redistanceSweepStaleCell(lattice, c, clamp, skipping.data(), stale.data()));
    }
    ASSERT_EQ(std::memcmp(full.data(), skipping.data(), full.size() * sizeof(double)), 0) << "half-sweep " << halfSweeps;
    ASSERT_EQ(dropFull, dropSkipping) << "half-sweep " << halfSweeps;
    changed = std::memcmp(before.data(), full.data(), full.size() * sizeof(double)) != 0;
  }
  std::printf("    %d half-sweeps to a fixed point, %.0f%% of the cell updates skipped\n", halfSweeps,
              100.0 * static_cast<double>(skipped) / static_cast<double>(updates));
  EXPECT_GT(skipped, 0);
}

TEST(FluidRedistance, FarCellsAreClampedAndBadInputRejected) {
  Field f = makeField(32, sphere, [](const Eigen::Vector3d&, double d) { return 10.0 * d; });
  RedistanceSettings settings;
  settings.bandCells = 3.0;
  redistance(f, settings);
  const double clamp = 3.0 * f.grid.spec.h;
  double largest = 0.0;
  for (size_t c = 0; c < f.phi.size(); ++c) {
    largest = std::max(largest, std::fabs(f.phi[c]));
    if (std::fabs(f.exact[c]) > clamp + f.grid.spec.h) {
      EXPECT_EQ(std::fabs(f.phi[c]), clamp);
    }
  }
  EXPECT_EQ(largest, clamp);
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  RedistanceWorkspace ws;
  settings.bandCells = 0.5;
  EXPECT_EQ(redistanceLevelSet(*tasks, f.grid.spec, f.phi.data(), settings, ws, nullptr), Status::InvalidArgument);
  EXPECT_EQ(redistanceLevelSet(*tasks, f.grid.spec, nullptr, RedistanceSettings{}, ws, nullptr),
            Status::InvalidArgument);
}

}  // namespace
}  // namespace vp

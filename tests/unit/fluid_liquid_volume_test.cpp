// Smoothed-Heaviside liquid volume and its correction by a uniform shift of phi.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid/mac_grid.h"
#include "fluid/surface/liquid_volume.h"
#include "fluid_liquid_test_util.h"

namespace vp {
namespace {

struct Drop {
  MacGrid grid;
  Array<double> phi;
};

Drop makeDrop(int n, const Eigen::Vector3d& centre, double radius) {
  Drop d;
  EXPECT_EQ(initMacGrid(testutil::unitCubeGrid(n), testutil::kClosedTank, &d.grid), Status::Ok);
  d.phi = testutil::sampleCells(d.grid, [&](const Eigen::Vector3d& x) { return (x - centre).norm() - radius; });
  return d;
}

// The smoothed Heaviside's curvature bias for a sphere: the volume exceeds 4/3 pi R^3 by
// 8 pi R e^2 * 2 int_0^1 H x dx = 8 pi R e^2 * 2 (1/6 - 1/pi^2) / 2 to leading order
// (liquid_volume.h), plus the midpoint-sampling error of a smooth integrand, O(h^2) and smaller.
TEST(FluidLiquidVolume, SphereVolumeMatchesWithKnownCurvatureBias) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double radius = 0.31;
  const Eigen::Vector3d centre(0.503, 0.49, 0.511);
  const double exact = 4.0 / 3.0 * M_PI * radius * radius * radius;
  for (int n : {32, 64}) {
    const Drop d = makeDrop(n, centre, radius);
    const double e = kDefaultHeavisideWidthCells * d.grid.spec.h;
    const double bias = 8.0 * M_PI * radius * e * e * (1.0 / 6.0 - 1.0 / (M_PI * M_PI));
    const double volume = liquidVolume(*tasks, d.grid.spec, d.phi.data(), nullptr);
    std::printf("    %d^3: relative error %.3e, predicted bias %.3e\n", n, volume / exact - 1.0, bias / exact);
    EXPECT_NEAR(volume, exact + bias, 0.1 * bias + 1e-3 * exact * (32.0 / n) * (32.0 / n));
    EXPECT_LT(std::fabs(volume / exact - 1.0), 0.01);
  }
}

TEST(FluidLiquidVolume, CorrectionRestoresVolumeAndRadiusAfterShift) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const double radius = 0.27;
  Drop d = makeDrop(48, {0.49, 0.52, 0.5}, radius);
  const MacGridSpec& spec = d.grid.spec;
  const double h = spec.h;
  const double target = liquidVolume(*tasks, spec, d.phi.data(), nullptr);
  for (double& p : d.phi) p += 0.3 * h;  // the drop lost a 0.3 h shell
  VolumeCorrectionResult result;
  ASSERT_EQ(correctLiquidVolume(*tasks, spec, d.phi.data(), nullptr, target, VolumeCorrectionSettings{}, &result),
            Status::Ok);
  const double after = liquidVolume(*tasks, spec, d.phi.data(), nullptr);
  std::printf("    shift %.6f h in %d iterations, volume before %.4e after %.10e (target %.10e)\n", result.shift / h,
              result.iterations, result.volumeBefore, after, target);
  EXPECT_TRUE(result.converged);
  EXPECT_LT(std::fabs(after / target - 1.0), 1e-6);
  EXPECT_LT(result.iterations, 6);  // Newton on a smooth monotone function
  // The radius is back: the shift undoes the 0.3 h up to the change of the curvature bias
  // with the radius (relative 0.3 h / R of a 0.4 % term: ~1e-4 h).
  EXPECT_NEAR(result.shift, -0.3 * h, 0.01 * h);
  // A target beyond the shift limit: moves by the limit and says it did not converge.
  ASSERT_EQ(correctLiquidVolume(*tasks, spec, d.phi.data(), nullptr, 2.0 * target, VolumeCorrectionSettings{}, &result),
            Status::Ok);
  EXPECT_FALSE(result.converged);
  EXPECT_NEAR(result.shift, -h, 1e-6 * h);
  EXPECT_EQ(correctLiquidVolume(*tasks, spec, d.phi.data(), nullptr, -1.0, VolumeCorrectionSettings{}, &result),
            Status::InvalidArgument);
}

// Cells inside a collider do not count: a half-full tank with a submerged box holds the water
// box minus the submerged solid, to the accuracy of the face-fraction cell estimate in the
// shell of cut cells (about the cut shell's volume times a few tens of percent).
TEST(FluidLiquidVolume, CellWeightsExcludeColliders) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  MacGrid grid;
  ASSERT_EQ(initMacGrid(testutil::unitCubeGrid(40), testutil::kClosedTank, &grid), Status::Ok);
  FaceFractionField fractions;
  ASSERT_EQ(initFaceFractionField(grid.spec, &fractions), Status::Ok);
  const ColliderShape box = testutil::tiltedBox({0.5, 0.3, 0.5});
  PreparedCollider collider;
  ASSERT_EQ(prepareCollider(box, &collider), Status::Ok);
  const PreparedCollider* list[] = {&collider};
  ASSERT_EQ(computeFaceFractions(list, 1, &fractions), Status::Ok);
  const double level = 0.6;
  const Array<double> phi = testutil::sampleCells(grid, [&](const Eigen::Vector3d& x) { return x.y() - level; });
  Array<double> weights;
  cellOpenFractions(*tasks, fractions, &weights);
  const double boxVolume = 8.0 * box.halfExtents.prod();
  const double exact = level - boxVolume;
  const double weighted = liquidVolume(*tasks, grid.spec, phi.data(), weights.data());
  const double unweighted = liquidVolume(*tasks, grid.spec, phi.data(), nullptr);
  std::printf("    water %.5f, unweighted %.5f, weighted %.5f (box %.5f)\n", exact, unweighted, weighted, boxVolume);
  EXPECT_NEAR(unweighted, level, 1e-3 * level);
  EXPECT_NEAR(weighted, exact, 0.05 * boxVolume);
}

}  // namespace
}  // namespace vp

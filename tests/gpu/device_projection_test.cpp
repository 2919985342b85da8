// The pressure projection on the CUDA device (gpu::DeviceProjection) against the CPU's
// projectVelocity on the same scene and operator (ctest label gpu; skipped by name without a
// device).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid/pressure/device_pressure_view.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/device_projection.h"
#include "gpu_kernels/device_query.h"

namespace vp::gpu_test {
namespace {

using testscene::PressureSceneKind;

class DeviceProjection : public ::testing::TestWithParam<PressureSceneKind> {
 protected:
  void SetUp() override {
    if (gpu::cudaDeviceCount() == 0) GTEST_SKIP() << "no CUDA device on this machine";
  }
};

double fluidNorm(const CutCellPoisson& op, const std::vector<double>& v) {
  double s = 0.0;
  for (size_t c = 0; c < v.size(); ++c)
    if (op.isFluid(c)) s += v[c] * v[c];
  return std::sqrt(s);
}

// A converged projection leaves |netOutflow(u)|_2 <= tolerance |netOutflow(u*)|_2 over the
// fluid cells (pressure_projection.h: netOutflow(u) = (dt / (rho h)) (L p - b)); the device's
// recursively updated residual drifts from the true one by O(u_double cond), far below the
// tolerance, so 1% above it is the bound. Both solves run the same MGPCG on the same operator;
// their iteration counts agree but for the last iteration crossing the threshold.
TEST_P(DeviceProjection, OneProjectionIsDivergenceFreeInTheCpuIterationCount) {
  constexpr double kDt = 0.02, kDensity = 1.0, kTolerance = 1e-6;
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  testscene::PressureScene scene;
  ASSERT_EQ(testscene::makePressureScene(*tasks, GetParam(), 32, &scene), Status::Ok) << lastError();
  const double* phi = scene.liquidPhi.empty() ? nullptr : scene.liquidPhi.data();
  MacGrid cpu = scene.grid, gpu = scene.grid;
  PressureSolveSettings settings;
  settings.tolerance = kTolerance;
  PressureState state;
  PressureSolveStats stats;
  ASSERT_EQ(projectVelocity(*tasks, cpu, scene.fractions, kDt, kDensity, Deadline(), settings, state, &stats, phi),
            Status::Ok)
      << lastError();
  ASSERT_TRUE(stats.converged);

  gpu::ProjectionView view;
  ASSERT_EQ(makeProjectionView(scene.grid, scene.fractions, state.poisson, state.multigrid, phi, &view), Status::Ok)
      << lastError();
  std::string error;
  auto device = gpu::DeviceProjection::create(view, &error);
  ASSERT_NE(device, nullptr) << error;
  std::vector<double> pressure(static_cast<size_t>(scene.grid.cellCount()), 0.0);
  double* const u[3] = {gpu.velocity[0].data(), gpu.velocity[1].data(), gpu.velocity[2].data()};
  gpu::DevicePressureResult result;
  ASSERT_TRUE(device->project(u, pressure.data(), kDt, kDensity, kTolerance, settings.maxIterations, &result, &error))
      << error;
  EXPECT_TRUE(result.converged);

  std::vector<double> before(pressure.size()), after(pressure.size());
  computeNetOutflow(*tasks, scene.grid, scene.fractions, state.poisson, before.data());
  computeNetOutflow(*tasks, gpu, scene.fractions, state.poisson, after.data());
  double largest = 0.0;
  for (int a = 0; a < 3; ++a)
    for (size_t f = 0; f < cpu.velocity[a].size(); ++f)
      largest = std::max(largest, std::abs(gpu.velocity[a][f] - cpu.velocity[a][f]));
  std::printf("    %s: CPU %d iterations, device %d; |div u| / |div u*| = %.3g; largest face difference %.3g\n",
              testscene::sceneName(GetParam()), stats.iterations, result.iterations,
              fluidNorm(state.poisson, after) / fluidNorm(state.poisson, before), largest);
  EXPECT_LE(fluidNorm(state.poisson, after), 1.01 * kTolerance * fluidNorm(state.poisson, before));
  EXPECT_LE(std::abs(result.iterations - stats.iterations), 1);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DeviceProjection,
                         ::testing::Values(PressureSceneKind::SmokeSphere, PressureSceneKind::LiquidTank),
                         [](const ::testing::TestParamInfo<PressureSceneKind>& param) {
                           return std::string(testscene::sceneName(param.param));
                         });

}  // namespace
}  // namespace vp::gpu_test

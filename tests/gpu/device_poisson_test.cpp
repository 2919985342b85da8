// The cut-cell pressure operator applied on the CUDA device against the CPU's rows (ctest label
// gpu; skipped by name without a device).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fluid/pressure/poisson_rows.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/device_poisson_operator.h"
#include "gpu_kernels/device_query.h"

namespace vp::gpu_test {
namespace {

using testscene::PressureSceneKind;

class DevicePoisson : public ::testing::TestWithParam<PressureSceneKind> {
 protected:
  void SetUp() override {
    if (gpu::cudaDeviceCount() == 0) GTEST_SKIP() << "no CUDA device on this machine";
  }
};

// Each cell's value sums the same seven products in the same order on both sides; only the
// device's fused multiply-adds round differently: within 2 * 7 u (|d x| + sum |A_f x_nb|).
TEST_P(DevicePoisson, TheOperatorMatchesTheCpuWithinRounding) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  testscene::PressureScene scene;
  ASSERT_EQ(testscene::makePressureScene(*tasks, GetParam(), 32, &scene), Status::Ok) << lastError();
  const CutCellPoisson& op = scene.poisson;
  const int64_t cells = scene.grid.cellCount();
  std::vector<double> x(static_cast<size_t>(cells)), cpu(x.size()), gpu(x.size()), magnitude(x.size());
  for (int64_t c = 0; c < cells; ++c) x[size_t(c)] = std::sin(0.013 * double(c)) + 0.2;
  applyCutCellPoisson(*tasks, op, x.data(), cpu.data());
  std::string error;
  auto device = gpu::DevicePoissonOperator::create(poisson_rows::Stencil<double>(op), &error);
  ASSERT_NE(device, nullptr) << error;
  ASSERT_TRUE(device->apply(x.data(), gpu.data(), &error)) << error;
  // |L| |x| per cell: the same stencil with absolute values.
  PoissonCoefficients<double> absolute;
  absolute.grid = op.grid;
  for (int a = 0; a < 3; ++a) {
    absolute.coupling[a] = op.coupling[a];
    for (double& v : absolute.coupling[a]) v = -std::abs(v);
  }
  absolute.diagonal = op.diagonal;
  std::vector<double> absX(x.size());
  for (size_t c = 0; c < x.size(); ++c) absX[c] = std::abs(x[c]);
  const poisson_rows::Stencil<double> absStencil(absolute);
  for (int64_t c = 0; c < cells; ++c) magnitude[size_t(c)] = kernels::poissonApplyCell(absStencil, c, absX.data());
  const double u = std::numeric_limits<double>::epsilon() / 2;
  int64_t fluid = 0;
  for (int64_t c = 0; c < cells; ++c) {
    fluid += op.diagonal[size_t(c)] > 0;
    ASSERT_LE(std::abs(gpu[size_t(c)] - cpu[size_t(c)]), 2 * 7 * u * magnitude[size_t(c)]) << "cell " << c;
  }
  EXPECT_GT(fluid, cells / 4);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DevicePoisson,
                         ::testing::Values(PressureSceneKind::SmokeSphere, PressureSceneKind::LiquidTank),
                         [](const ::testing::TestParamInfo<PressureSceneKind>& param) {
                           return std::string(testscene::sceneName(param.param));
                         });

}  // namespace
}  // namespace vp::gpu_test

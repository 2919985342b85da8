// Velocity advection on the CUDA device (gpu::DeviceVelocityAdvection) against the CPU's
// advectVelocity: the same kernel bodies, compiled without contraction on the device, so the
// same bits on every face, for several steps in a row (ctest label gpu; skipped by name
// without a device).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "fluid/advection/advection.h"
#include "fluid/advection/advection_rows.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/device_query.h"
#include "gpu_kernels/device_velocity_advection.h"

namespace vp::gpu_test {
namespace {

class DeviceAdvection : public ::testing::TestWithParam<AdvectionScheme> {
 protected:
  void SetUp() override {
    if (gpu::cudaDeviceCount() == 0) GTEST_SKIP() << "no CUDA device on this machine";
  }
};

// A grid that is not a cube and not at the origin, with the pressure scenes' swirl plus random
// speeds of a few cells per step, so traces leave the domain and get clamped.
MacGrid swirlGrid() {
  MacGridSpec spec;
  spec.origin = Vec3(0.1, -0.2, 0.3);
  spec.h = 1.0 / 40;
  spec.nx = 40;
  spec.ny = 27;
  spec.nz = 33;
  MacGrid g;
  EXPECT_EQ(initMacGrid(spec, {}, &g), Status::Ok);
  testscene::fillSwirl(g);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  for (int a = 0; a < 3; ++a)
    for (double& u : g.velocity[a]) u += jitter(rng);
  return g;
}

TEST_P(DeviceAdvection, FiveStepsGiveTheCpuBitsOnEveryFace) {
  const bool maccormack = GetParam() == AdvectionScheme::MacCormack;
  constexpr double kDt = 0.03;
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  MacGrid cpu = swirlGrid();
  std::string error;
  auto device = gpu::DeviceVelocityAdvection::create(macVelocityView(cpu), &error);
  ASSERT_NE(device, nullptr) << error;
  AdvectionWorkspace work;
  MacGrid gpu = cpu;
  for (int step = 0; step < 5; ++step) {
    advectVelocity(*tasks, cpu, kDt, GetParam(), work);
    ASSERT_TRUE(device->advect(kDt, maccormack, &error)) << error;
  }
  double* const u[3] = {gpu.velocity[0].data(), gpu.velocity[1].data(), gpu.velocity[2].data()};
  ASSERT_TRUE(device->download(u, &error)) << error;
  for (int a = 0; a < 3; ++a) {
    size_t differing = 0;
    double largest = 0.0;
    for (size_t f = 0; f < cpu.velocity[a].size(); ++f) {
      const double d = std::abs(gpu.velocity[a][f] - cpu.velocity[a][f]);
      differing += gpu.velocity[a][f] != cpu.velocity[a][f];
      largest = std::max(largest, d);
    }
    std::printf("    axis %d: %zu of %zu faces differ, largest difference %.3g\n", a, differing,
                cpu.velocity[a].size(), largest);
    EXPECT_EQ(differing, 0u) << "axis " << a;
  }
}

INSTANTIATE_TEST_SUITE_P(Schemes, DeviceAdvection,
                         ::testing::Values(AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack),
                         [](const ::testing::TestParamInfo<AdvectionScheme>& param) {
                           return param.param == AdvectionScheme::MacCormack ? std::string("maccormack")
                                                                              : std::string("semi_lagrangian");
                         });

}  // namespace
}  // namespace vp::gpu_test

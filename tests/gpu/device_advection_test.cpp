// Advection on the CUDA device (gpu::DeviceAdvection) against the CPU's advectVelocity and
// advectCellScalars: the same kernel bodies, compiled without contraction on the device, and
// the conserved field's sums in the same order, so the same bits on every face and cell
// (ctest label gpu; skipped by name without a device).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "fluid/advection/advection.h"
#include "fluid/advection/advection_rows.h"
#include "fluid_pressure_scenes.h"
#include "fluid/solids/face_fraction_field.h"
#include "gpu_kernels/device_query.h"
#include "gpu_kernels/device_advection.h"

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
  auto device = gpu::DeviceAdvection::create(macVelocityView(cpu), cpu.layout(), &error);
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

// Smoke's scalars past the pressure scenes' sphere: density (conserved, 0 in solids) and
// temperature, through open faces only, with the scene's Open top, three steps.
TEST_P(DeviceAdvection, ScalarsGiveTheCpuBitsOnEveryCell) {
  const bool maccormack = GetParam() == AdvectionScheme::MacCormack;
  constexpr double kDt = 0.03;
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  testscene::PressureScene scene;
  ASSERT_EQ(testscene::makePressureScene(*tasks, testscene::PressureSceneKind::SmokeSphere, 32, &scene), Status::Ok)
      << lastError();
  CellOpenFaces masks;
  buildCellOpenFaces(*tasks, scene.grid, scene.fractions, &masks);
  const size_t cells = static_cast<size_t>(scene.grid.cellCount());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Array<double>> cpu(2, Array<double>(cells));
  for (Array<double>& field : cpu)
    for (double& x : field) x = unit(rng);
  std::vector<Array<double>> gpu = cpu;
  const double solidValues[2] = {0.0, 0.0};
  std::string error;
  auto device = gpu::DeviceAdvection::create(macVelocityView(scene.grid), scene.grid.layout(), &error);
  ASSERT_NE(device, nullptr) << error;
  gpu::ScalarAdvectionOptions options;
  options.faces = masks.faces.data();
  options.blockOpen = masks.blockOpen.data();
  options.solidValues = solidValues;
  options.conservedField = 0;
  AdvectionWorkspace work;
  for (int step = 0; step < 3; ++step) {
    Array<double>* fields[2] = {&cpu[0], &cpu[1]};
    advectCellScalars(*tasks, scene.grid, kDt, GetParam(), fields, 2, work, &masks, solidValues, 0.0, 0);
    double* const onDevice[2] = {gpu[0].data(), gpu[1].data()};
    ASSERT_TRUE(device->advectScalars(onDevice, 2, kDt, maccormack, options, &error)) << error;
  }
  for (int f = 0; f < 2; ++f) {
    size_t differing = 0;
    for (size_t c = 0; c < cells; ++c) differing += gpu[size_t(f)][c] != cpu[size_t(f)][c];
    std::printf("    field %d: %zu of %zu cells differ\n", f, differing, cells);
    EXPECT_EQ(differing, 0u) << "field " << f;
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

// The cut-cell pressure solve on the CUDA device (gpu::DevicePressureSolver) against the CPU's
// (applyPoissonMultigrid, the CG of SceneSolver) on the same hierarchy: one V-cycle, and a
// solve to 1e-6 (ctest label gpu; skipped by name without a device).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fluid/pressure/device_pressure_view.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/device_pressure_solver.h"
#include "gpu_kernels/device_query.h"

namespace vp::gpu_test {
namespace {

using testscene::PressureSceneKind;

constexpr int kSize = 32;

class DevicePressureSolve : public ::testing::TestWithParam<PressureSceneKind> {
 protected:
  void SetUp() override {
    if (gpu::cudaDeviceCount() == 0) GTEST_SKIP() << "no CUDA device on this machine";
    tasks = TaskSystem::create(TaskHooks{}, 2);
    ASSERT_EQ(testscene::makeSceneWithMultigrid(*tasks, GetParam(), kSize, &scene, &solver), Status::Ok)
        << lastError();
    gpu::PressureSolveView view;
    ASSERT_EQ(makePressureSolveView(scene.poisson, solver.mg, &view), Status::Ok) << lastError();
    std::string error;
    device = gpu::DevicePressureSolver::create(view, &error);
    ASSERT_NE(device, nullptr) << error;
  }

  // Passes over a level's values in one cycle, each rounding every value once in single
  // precision: per level below the coarsest the sweeps and boundary sweeps before and after,
  // the residual, three restriction gathers and the prolongation; on the coarsest its sweeps.
  int passesPerCycle() const {
    const MultigridSettings& s = solver.mg.settings;
    const int levels = solver.mg.levelCount();
    return (levels - 1) * (2 * (s.sweeps + s.boundarySweeps) + 5) + 2 * s.coarsestSweeps;
  }

  std::unique_ptr<TaskSystem> tasks;
  testscene::PressureScene scene;
  testscene::SceneSolver solver;
  std::unique_ptr<gpu::DevicePressureSolver> device;
};

double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

// The device runs the CPU's cycle stage for stage through the same kernel bodies; only its fused
// multiply-adds (and the order of a floating region's sum) round differently. Each pass of the
// cycle rounds every value once in single precision (u = 2^-24) and the smoothers and
// transfers do not amplify what earlier passes left (Gauss-Seidel contracts the error in the
// energy norm): the two cycles differ by at most about passes * u relative; 4x that is the bound.
TEST_P(DevicePressureSolve, OneVcycleMatchesTheCpuWithinSinglePrecisionRounding) {
  std::vector<double> r = scene.rhs;
  filterCutCellPoisson(*tasks, scene.poisson, r.data());
  std::vector<double> cpu(r.size()), gpu(r.size());
  applyPoissonMultigrid(*tasks, scene.poisson, solver.mg, r.data(), cpu.data());
  std::string error;
  ASSERT_TRUE(device->vcycle(r.data(), gpu.data(), &error)) << error;
  std::vector<double> difference(r.size());
  for (size_t c = 0; c < r.size(); ++c) difference[c] = gpu[c] - cpu[c];
  const double u = std::numeric_limits<float>::epsilon() / 2;
  const double relative = norm(difference) / norm(cpu);
  std::printf("    %s: |z_gpu - z_cpu| / |z_cpu| = %.3g (bound %.3g over %d passes)\n",
              testscene::sceneName(GetParam()), relative, 4 * passesPerCycle() * u, passesPerCycle());
  EXPECT_GT(norm(cpu), 0.0);
  EXPECT_LE(relative, 4 * passesPerCycle() * u);
}

// Both CGs stop at |r| <= 1e-6 |b|. The preconditioners differ by round-off only, so the
// iteration counts agree but for the last iteration crossing the threshold (+-1); the device's
// x leaves a true residual b - A x (recomputed here in double on the CPU) within 1% of the
// tolerance: the recursively updated residual drifts from the true one by O(u_double * cond),
// orders of magnitude below 1e-6.
TEST_P(DevicePressureSolve, MgpcgConvergesInTheCpuIterationCount) {
  constexpr double kTolerance = 1e-6;
  std::vector<double> cpuX;
  const CgResult cpu = solver.solve(*tasks, scene, kTolerance, 200, &cpuX);
  ASSERT_TRUE(cpu.converged);
  std::vector<double> x(scene.rhs.size());
  gpu::DevicePressureResult result;
  std::string error;
  ASSERT_TRUE(device->solve(scene.rhs.data(), x.data(), kTolerance, 200, &result, &error)) << error;
  std::printf("    %s: CPU %d iterations, device %d (%.3g ms, relative residual %.3g)\n",
              testscene::sceneName(GetParam()), cpu.iterations, result.iterations, result.ms,
              result.relativeResidual);
  EXPECT_TRUE(result.converged);
  EXPECT_LE(std::abs(result.iterations - cpu.iterations), 1);
  std::vector<double> ax(x.size()), residual(x.size()), b = scene.rhs;
  applyCutCellPoisson(*tasks, scene.poisson, x.data(), ax.data());
  for (size_t c = 0; c < x.size(); ++c) residual[c] = scene.rhs[c] - ax[c];
  filterCutCellPoisson(*tasks, scene.poisson, residual.data());
  filterCutCellPoisson(*tasks, scene.poisson, b.data());
  EXPECT_LE(norm(residual) / norm(b), 1.01 * kTolerance);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DevicePressureSolve,
                         ::testing::Values(PressureSceneKind::SmokeSphere, PressureSceneKind::ClosedTank,
                                           PressureSceneKind::LiquidTank),
                         [](const ::testing::TestParamInfo<PressureSceneKind>& param) {
                           return std::string(testscene::sceneName(param.param));
                         });

}  // namespace
}  // namespace vp::gpu_test

// The cut-cell pressure operator (an implicit 7-point stencil: couplings and diagonal, no
// stored matrix) applied once, on the pressure benchmarks' scenes (tests/unit/
// fluid_pressure_scenes.h) at n^3 cells:
//   BM_GpuPoissonApply/{smoke_sphere,liquid_tank}/{128,256}   one thread per cell on the device,
//       device events over a batch;
//   BM_CpuPoissonApply/{smoke_sphere,liquid_tank}/128   the CPU's row kernels, 2 worker threads.
// Counters: mcells_per_s (all cells), gbps (the couplings, diagonal, x and y once, doubles).
// Figures: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "fluid/pressure/poisson_rows.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/device_poisson_operator.h"
#include "gpu_kernels/device_query.h"

namespace vp::gpu_test {
namespace {

using testscene::PressureSceneKind;

struct SceneCase {
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  testscene::PressureScene scene;
  bool ok = false;
};

SceneCase& sceneCase(PressureSceneKind kind, int n) {
  static std::map<std::pair<int, int>, std::unique_ptr<SceneCase>> cases;
  std::unique_ptr<SceneCase>& c = cases[{static_cast<int>(kind), n}];
  if (!c) {
    c = std::make_unique<SceneCase>();
    c->ok = ok(testscene::makePressureScene(*c->tasks, kind, n, &c->scene));
  }
  return *c;
}

void count(benchmark::State& state, const testscene::PressureScene& scene, double msPerApply) {
  const double cells = double(scene.grid.cellCount());
  state.counters["mcells_per_s"] = cells / (msPerApply / 1000.0) / 1e6;
  state.counters["gbps"] = (3.0 + 1.0 + 2.0) * cells * sizeof(double) / (msPerApply / 1000.0) / 1e9;
}

void BM_GpuPoissonApply(benchmark::State& state, PressureSceneKind kind, int n) {
  if (gpu::cudaDeviceCount() == 0) return state.SkipWithError("no CUDA device");
  SceneCase& c = sceneCase(kind, n);
  if (!c.ok) return state.SkipWithError("scene setup failed");
  std::string error;
  auto device = gpu::DevicePoissonOperator::create(poisson_rows::Stencil<double>(c.scene.poisson), &error);
  if (!device) return state.SkipWithError(error.c_str());
  double ms = 0;
  for (auto _ : state) {
    if (!device->timeApply(20, &ms, &error)) return state.SkipWithError(error.c_str());
    state.SetIterationTime(ms / 1000.0);
  }
  count(state, c.scene, ms);
}

void BM_CpuPoissonApply(benchmark::State& state, PressureSceneKind kind, int n) {
  SceneCase& c = sceneCase(kind, n);
  if (!c.ok) return state.SkipWithError("scene setup failed");
  std::vector<double> x(static_cast<size_t>(c.scene.grid.cellCount()), 1.0), y(x.size());
  for (auto _ : state) {
    applyCutCellPoisson(*c.tasks, c.scene.poisson, x.data(), y.data());
    benchmark::DoNotOptimize(y.data());
  }
  const double cells = double(c.scene.grid.cellCount()) * double(state.iterations());
  state.counters["mcells_per_s"] = benchmark::Counter(cells / 1e6, benchmark::Counter::kIsRate);
  state.counters["gbps"] = benchmark::Counter(6.0 * cells * sizeof(double) / 1e9, benchmark::Counter::kIsRate);
}

const bool registered = [] {
  for (PressureSceneKind kind : {PressureSceneKind::SmokeSphere, PressureSceneKind::LiquidTank}) {
    const std::string scene = testscene::sceneName(kind);
    for (int n : {128, 256})
      benchmark::RegisterBenchmark(("BM_GpuPoissonApply/" + scene + "/" + std::to_string(n)).c_str(),
                                   [kind, n](benchmark::State& s) { BM_GpuPoissonApply(s, kind, n); })
          ->UseManualTime()
          ->Unit(benchmark::kMicrosecond)
          ->Iterations(10)
          ->Repetitions(5);
    benchmark::RegisterBenchmark(("BM_CpuPoissonApply/" + scene + "/128").c_str(),
                                 [kind](benchmark::State& s) { BM_CpuPoissonApply(s, kind, 128); })
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond)
        ->Repetitions(3);
  }
  return true;
}();

}  // namespace
}  // namespace vp::gpu_test

// The cut-cell MGPCG pressure solve on the device (gpu::DevicePressureSolver) on the pressure
// benchmarks' scenes (tests/unit/fluid_pressure_scenes.h) at n^3 cells, from p = 0 to a
// relative residual of 1e-6, the hierarchy built on the CPU and uploaded:
//   BM_GpuPressureSolve/cutcell_mgpcg/{smoke_sphere,liquid_tank}/{128,256}
// Counters
//   ms                the solve on the device (device events; the host reads three scalars per
//                     iteration, which the figure includes)
//   iters             CG iterations
//   vcycle_ms, apply_ms  one V-cycle (the recorded graph) and one fine operator application,
//                     resident vectors, device events over a batch; vcycle_per_matvec their ratio
//   upload_ms         creating the device solver: the levels' upload and the graph's recording
//   setup_ms          building the multigrid on the CPU (2 worker threads), which a step whose
//                     operator changed pays today before the upload
//   cpu_ms            (128 only) the CPU's own solve of the same system, 2 worker threads on
//                     the same machine, in the same run
// Figures: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <string>

#include "fluid/pressure/device_pressure_view.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/device_pressure_solver.h"
#include "gpu_kernels/device_query.h"

namespace vp::gpu_test {
namespace {

using testscene::PressureSceneKind;

constexpr double kTolerance = 1e-6;
constexpr int kMaxIterations = 200;

struct SolveCase {
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  testscene::PressureScene scene;
  testscene::SceneSolver solver;
  double setupMs = 0.0;
  bool ok = false;
};

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

SolveCase& solveCase(PressureSceneKind kind, int n) {
  static std::map<std::pair<int, int>, std::unique_ptr<SolveCase>> cases;
  std::unique_ptr<SolveCase>& c = cases[{static_cast<int>(kind), n}];
  if (!c) {
    c = std::make_unique<SolveCase>();
    c->ok = ok(testscene::makePressureScene(*c->tasks, kind, n, &c->scene));
    const auto start = std::chrono::steady_clock::now();
    c->ok = c->ok && ok(c->solver.prepare(*c->tasks, c->scene));
    c->setupMs = msSince(start);
  }
  return *c;
}

void BM_GpuPressureSolve(benchmark::State& state, PressureSceneKind kind, int n) {
  if (gpu::cudaDeviceCount() == 0) return state.SkipWithError("no CUDA device");
  SolveCase& c = solveCase(kind, n);
  if (!c.ok) return state.SkipWithError("scene setup failed");
  gpu::PressureSolveView view;
  if (!ok(makePressureSolveView(c.scene.poisson, c.solver.mg, &view))) return state.SkipWithError(lastError());
  std::string error;
  const auto start = std::chrono::steady_clock::now();
  auto device = gpu::DevicePressureSolver::create(view, &error);
  const double uploadMs = msSince(start);
  if (!device) return state.SkipWithError(error.c_str());
  std::vector<double> x(c.scene.rhs.size());
  gpu::DevicePressureResult result;
  for (auto _ : state) {
    std::fill(x.begin(), x.end(), 0.0);  // from p = 0, as BM_PressureSolve
    if (!device->solve(c.scene.rhs.data(), x.data(), kTolerance, kMaxIterations, &result, &error))
      return state.SkipWithError(error.c_str());
    if (!result.converged) return state.SkipWithError("device pressure solve did not converge");
    state.SetIterationTime(result.ms / 1000.0);
  }
  double vcycleMs = 0.0, applyMs = 0.0;
  if (!device->timeVcycle(20, &vcycleMs, &applyMs, &error)) return state.SkipWithError(error.c_str());
  state.counters["ms"] = result.ms;
  state.counters["iters"] = result.iterations;
  state.counters["vcycle_ms"] = vcycleMs;
  state.counters["apply_ms"] = applyMs;
  state.counters["vcycle_per_matvec"] = vcycleMs / applyMs;
  state.counters["upload_ms"] = uploadMs;
  state.counters["setup_ms"] = c.setupMs;
  if (n == 128) {
    std::vector<double> p;
    const auto cpuStart = std::chrono::steady_clock::now();
    const CgResult cpu = c.solver.solve(*c.tasks, c.scene, kTolerance, kMaxIterations, &p);
    state.counters["cpu_ms"] = msSince(cpuStart);
    state.counters["cpu_iters"] = cpu.iterations;
  }
}

const bool registered = [] {
  for (PressureSceneKind kind : {PressureSceneKind::SmokeSphere, PressureSceneKind::LiquidTank})
    for (int n : {128, 256})
      benchmark::RegisterBenchmark(
          ("BM_GpuPressureSolve/cutcell_mgpcg/" + std::string(testscene::sceneName(kind)) + "/" + std::to_string(n))
              .c_str(),
          [kind, n](benchmark::State& s) { BM_GpuPressureSolve(s, kind, n); })
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(5)
          ->Repetitions(3);
  return true;
}();

}  // namespace
}  // namespace vp::gpu_test

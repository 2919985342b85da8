// Velocity advection of an n^3 MAC grid by itself (the pressure scenes' swirl velocity), one
// step of dt = 0.5 h (half a cell at unit speed):
//   BM_GpuVelocityAdvection/{semi_lagrangian,maccormack}/{128,256}   one thread per face on the
//       device (gpu::DeviceAdvection), device events over a batch of steps;
//   BM_CpuVelocityAdvection/{semi_lagrangian,maccormack}/128   advectVelocity, 2 worker
//       threads, the same run.
// Counters: ms per step, mfaces_per_s (faces of the three axes per second).
// Figures: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "fluid/advection/advection.h"
#include "fluid/advection/advection_rows.h"
#include "fluid_pressure_scenes.h"
#include "gpu_kernels/device_query.h"
#include "gpu_kernels/device_advection.h"

namespace vp::gpu_test {
namespace {

MacGrid swirlCube(int n) {
  MacGridSpec spec;
  spec.h = 1.0 / n;
  spec.nx = spec.ny = spec.nz = n;
  MacGrid g;
  if (initMacGrid(spec, {}, &g) == Status::Ok) testscene::fillSwirl(g);
  return g;
}

double faceCount(const MacGrid& g) {
  return double(g.velocity[0].size() + g.velocity[1].size() + g.velocity[2].size());
}

void BM_GpuVelocityAdvection(benchmark::State& state, bool maccormack, int n) {
  if (gpu::cudaDeviceCount() == 0) return state.SkipWithError("no CUDA device");
  const MacGrid grid = swirlCube(n);
  std::string error;
  auto device = gpu::DeviceAdvection::create(macVelocityView(grid), grid.layout(), &error);
  if (!device) return state.SkipWithError(error.c_str());
  double ms = 0.0;
  for (auto _ : state) {
    if (!device->timeAdvect(5, 0.5 * grid.spec.h, maccormack, &ms, &error)) return state.SkipWithError(error.c_str());
    state.SetIterationTime(ms / 1000.0);
  }
  state.counters["ms"] = ms;
  state.counters["mfaces_per_s"] = faceCount(grid) / (ms / 1000.0) / 1e6;
}

void BM_CpuVelocityAdvection(benchmark::State& state, AdvectionScheme scheme, int n) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  MacGrid grid = swirlCube(n);
  AdvectionWorkspace work;
  for (auto _ : state) advectVelocity(*tasks, grid, 0.5 * grid.spec.h, scheme, work);
  state.counters["mfaces_per_s"] =
      benchmark::Counter(faceCount(grid) * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}

const bool registered = [] {
  for (AdvectionScheme scheme : {AdvectionScheme::SemiLagrangian, AdvectionScheme::MacCormack}) {
    const bool maccormack = scheme == AdvectionScheme::MacCormack;
    const std::string name = maccormack ? "maccormack" : "semi_lagrangian";
    for (int n : {128, 256})
      benchmark::RegisterBenchmark(("BM_GpuVelocityAdvection/" + name + "/" + std::to_string(n)).c_str(),
                                   [maccormack, n](benchmark::State& s) { BM_GpuVelocityAdvection(s, maccormack, n); })
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(4)
          ->Repetitions(3);
    benchmark::RegisterBenchmark(("BM_CpuVelocityAdvection/" + name + "/128").c_str(),
                                 [scheme](benchmark::State& s) { BM_CpuVelocityAdvection(s, scheme, 128); })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(3)
        ->Repetitions(3);
  }
  return true;
}();

}  // namespace
}  // namespace vp::gpu_test

// Rigid-only world step and the deterministic parallel reduction that the solvers build on.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "core/parallel_for.h"
#include "scene/scene_loader.h"
#include "world.h"

namespace vp {
namespace {

void BM_WorldStepRigidScene(benchmark::State& state) {
  WorldConfig config;
  std::unique_ptr<World> world;
  World::create(config, &world);
  if (!ok(loadScene(*world, VP_TEST_DATA_DIR "/scenes/stack.json"))) {
    state.SkipWithError(lastError());
    return;
  }
  for (auto _ : state) world->step(1.0 / 60.0);
  state.counters["hz"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WorldStepRigidScene)->Unit(benchmark::kMicrosecond);

// Dot product of 4M doubles with 1 or 2 workers: the reduction pattern CG uses.
void BM_ParallelDot(benchmark::State& state) {
  const int workers = static_cast<int>(state.range(0));
  auto tasks = TaskSystem::create(TaskHooks{}, workers);
  const int64_t n = 1 << 22;
  std::vector<double> x(n), y(n);
  for (int64_t i = 0; i < n; ++i) x[i] = std::sin(double(i)), y[i] = std::cos(double(i));
  double sink = 0;
  for (auto _ : state) {
    sink += parallelReduce<double>(*tasks, n, 1 << 14, [&](int64_t b, int64_t e) {
      double s = 0;
      for (int64_t i = b; i < e; ++i) s += x[i] * y[i];
      return s;
    });
  }
  benchmark::DoNotOptimize(sink);
  state.counters["gbps"] =
      benchmark::Counter(double(state.iterations()) * 2.0 * n * sizeof(double) / 1e9, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ParallelDot)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace vp

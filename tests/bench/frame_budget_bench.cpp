// The default scene under real frame budgets: how the step time distributes against the
// budget, and what the world gives up to stay near it: the solvers' final residual, and the
// fluid steps the pacing defers (fluid_step_frac: fluid steps taken per fluid and frame).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "scene/scene_loader.h"
#include "world.h"

namespace vp {
namespace {

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const size_t rank = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
  return v[rank];
}

void BM_FrameBudget(benchmark::State& state) {
  const double budgetMs = static_cast<double>(state.range(0));
  const int frames = 300;
  for (auto _ : state) {
    WorldConfig config;
    config.workerCount = 2;
    std::unique_ptr<World> world;
    World::create(config, &world);
    if (!ok(loadScene(*world, VP_SAMPLE_SCENE))) return state.SkipWithError(lastError());
    world->setFrameBudget(budgetMs);
    std::vector<double> ms;
    double residualSum = 0.0;
    int residualCount = 0, cutFrames = 0, fluidSlots = 0, fluidSteps = 0;
    for (int f = 0; f < frames; ++f) {
      world->step(1.0 / 60.0);
      const StepStats& s = world->lastStats();
      ms.push_back(s.totalMs);
      cutFrames += s.budgetCut;
      for (const ActorStats& a : s.actors)
        if (a.kind == ActorKind::Deformable) {
          residualSum += a.phase(Phase::Solve).residual, ++residualCount;
        } else if (a.kind == ActorKind::Fluid) {
          ++fluidSlots;
          fluidSteps += a.simulatedDt > 0.0;
        }
    }
    state.counters["p50_ms"] = percentile(ms, 0.50);
    state.counters["p95_ms"] = percentile(ms, 0.95);
    state.counters["p99_ms"] = percentile(ms, 0.99);
    state.counters["overrun_frac"] =
        double(std::count_if(ms.begin(), ms.end(), [&](double m) { return m > 1.1 * budgetMs; })) / frames;
    state.counters["cut_frac"] = double(cutFrames) / frames;
    state.counters["fluid_step_frac"] = fluidSlots ? double(fluidSteps) / fluidSlots : 1.0;
    state.counters["mean_residual"] = residualCount ? residualSum / residualCount : 0.0;
  }
}
BENCHMARK(BM_FrameBudget)->Arg(8)->Arg(16)->Arg(33)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace vp

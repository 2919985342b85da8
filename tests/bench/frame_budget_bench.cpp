// The default scene under real frame budgets (frame_plan.h): how the step time distributes
// against the budget and what the world gives up to stay within it.
//   overrun_frac         frames above 1.1 x budget
//   p50_ms, p99_ms       frame time percentiles
//   deform_residual_p95  95th percentile of the deformables' final relative residual
//   fluid_rate           simulated seconds per frame second, mean over the fluids
//   max_slice_ms         the longest single slice of work seen
//   max_slice_p99_ms     99th percentile over the frames of each frame's longest slice, and
//   slice_over_frac      the frames whose longest slice took more than a quarter of the
//                        budget: with max_slice_ms they tell a slice's own cost (every frame
//                        has several of similar size) from a rare preemption of a thread
//   fluid_interval_max   the largest number of frames a fluid step spanned
// BM_FrameBudgetLoaded runs the same while one extra process keeps a core busy (started and
// stopped by the benchmark): the budget must hold on a busier machine too.
#include <benchmark/benchmark.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <vector>

#include "default_scene.h"

namespace vp {
namespace {

using bench::percentile;

// A child process that spins until killed, or until the benchmark dies (a benchmark killed
// part way, e.g. by a closed pipe, would otherwise leave it spinning and load every later
// measurement).
class BusyProcess {
 public:
  BusyProcess() {
    const pid_t parent = getpid();
    pid_ = fork();
    if (pid_ == 0) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) _exit(0);  // the parent died before prctl
      volatile unsigned long spin = 0;
      for (;;) spin = spin + 1;
    }
  }
  ~BusyProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  BusyProcess(const BusyProcess&) = delete;
  BusyProcess& operator=(const BusyProcess&) = delete;

 private:
  pid_t pid_ = -1;
};

void runDefaultScene(benchmark::State& state, double budgetMs) {
  const int frames = 300;
  const double dt = 1.0 / 60.0;
  for (auto _ : state) {
    std::unique_ptr<World> world = bench::defaultSceneWorld();
    if (!world) return state.SkipWithError(lastError());
    world->setFrameBudget(budgetMs);
    std::vector<double> ms, residuals, frameSlices;
    double fluidSimulated = 0.0;
    int fluidCount = 0, fluidIntervalMax = 1;
    for (int f = 0; f < frames; ++f) {
      world->step(dt);
      const StepStats& s = world->lastStats();
      ms.push_back(s.totalMs);
      frameSlices.push_back(s.maxSliceMs);
      for (const ActorStats& a : s.actors)
        if (a.kind == ActorKind::Deformable && a.completedStep) {
          residuals.push_back(a.residual);
        } else if (a.kind == ActorKind::Fluid) {
          fluidSimulated += a.simulatedDt;
          fluidIntervalMax = std::max(fluidIntervalMax, a.interval);
          if (f == 0) ++fluidCount;
        }
    }
    state.counters["p50_ms"] = percentile(ms, 0.50);
    state.counters["p99_ms"] = percentile(ms, 0.99);
    state.counters["overrun_frac"] =
        double(std::count_if(ms.begin(), ms.end(), [&](double m) { return m > 1.1 * budgetMs; })) / frames;
    state.counters["deform_residual_p95"] = percentile(residuals, 0.95);
    state.counters["fluid_rate"] = fluidCount ? fluidSimulated / fluidCount / (frames * dt) : 1.0;
    state.counters["max_slice_ms"] = *std::max_element(frameSlices.begin(), frameSlices.end());
    state.counters["max_slice_p99_ms"] = percentile(frameSlices, 0.99);
    state.counters["slice_over_frac"] =
        double(std::count_if(frameSlices.begin(), frameSlices.end(), [&](double m) { return m > budgetMs / 4; })) / frames;
    state.counters["fluid_interval_max"] = fluidIntervalMax;
  }
}

void BM_FrameBudget(benchmark::State& state) { runDefaultScene(state, static_cast<double>(state.range(0))); }
BENCHMARK(BM_FrameBudget)->Arg(8)->Arg(16)->Arg(33)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_FrameBudgetLoaded(benchmark::State& state) {
  BusyProcess busy;
  runDefaultScene(state, static_cast<double>(state.range(0)));
}
BENCHMARK(BM_FrameBudgetLoaded)->Arg(16)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace vp

// The default scene for a long run under its frame budget: does anything go wrong only after
// thousands of frames (a NaN, a divergence, memory that keeps growing, frames that get slower)?
//   BM_Soak/N   N frames of 1/60 s at the scene's 16 ms budget, two workers.
// Counters:
//   nan_frames        frames after which any collider pose, deformable node or fluid
//                     velocity, smoke or level-set value was not finite
//   diverged          actor-steps flagged diverged (restored by the divergence guard)
//   rss_start_mb      resident memory after loading the scene
//   rss_500_mb        ... after 500 frames (caches, pools and the fluids' workspaces are warm)
//   rss_end_mb        ... after the last frame
//   rss_growth_frac   (rss_end - rss_500) / rss_500: must stay below 0.05
//   p50_ms, p99_ms    frame time percentiles; p99_last_ms the same over the last 1000 frames
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "default_scene.h"

namespace vp {
namespace {

using bench::percentile;

double residentMb() {
  long pages = 0, resident = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

template <class Range>
bool allFinite(const Range& values) {
  return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}

bool worldIsFinite(const World& world) {
  for (ColliderHandle h : world.colliderHandles()) {
    const Pose p = world.collider(h)->pose();
    if (!p.position.allFinite() || !p.rotation.coeffs().allFinite()) return false;
  }
  for (DeformableHandle h : world.deformableHandles())
    if (!allFinite(world.deformable(h)->positions())) return false;
  for (FluidHandle h : world.fluidHandles()) {
    const FluidActor& f = *world.fluid(h);
    for (int a = 0; a < 3; ++a)
      if (!allFinite(f.grid().velocity[a])) return false;
    if (!allFinite(f.smokeDensity()) || !allFinite(f.levelSet())) return false;
  }
  return true;
}

void BM_Soak(benchmark::State& state) {
  const int frames = static_cast<int>(state.range(0));
  for (auto _ : state) {
    std::unique_ptr<World> world = bench::defaultSceneWorld();
    if (!world) return state.SkipWithError(lastError());
    const double rssStart = residentMb();
    double rss500 = rssStart;
    std::vector<double> ms;
    ms.reserve(static_cast<size_t>(frames));
    int nanFrames = 0, diverged = 0;
    for (int f = 0; f < frames; ++f) {
      world->step(1.0 / 60.0);
      const StepStats& s = world->lastStats();
      ms.push_back(s.totalMs);
      for (const ActorStats& a : s.actors) diverged += a.diverged ? 1 : 0;
      nanFrames += worldIsFinite(*world) ? 0 : 1;
      if (f + 1 == std::min(500, frames)) rss500 = residentMb();
    }
    const double rssEnd = residentMb();
    state.counters["nan_frames"] = nanFrames;
    state.counters["diverged"] = diverged;
    state.counters["rss_start_mb"] = rssStart;
    state.counters["rss_500_mb"] = rss500;
    state.counters["rss_end_mb"] = rssEnd;
    state.counters["rss_growth_frac"] = (rssEnd - rss500) / rss500;
    state.counters["p50_ms"] = percentile(ms, 0.50);
    state.counters["p99_ms"] = percentile(ms, 0.99);
    const std::vector<double> last(ms.end() - std::min<ptrdiff_t>(1000, ptrdiff_t(ms.size())), ms.end());
    state.counters["p99_last_ms"] = percentile(last, 0.99);
  }
}
BENCHMARK(BM_Soak)->Arg(10000)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace vp

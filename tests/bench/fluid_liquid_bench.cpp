// Per-step cost of the liquid numerics on a dam-break-like level set (a water block in one
// corner plus a drop): redistancing, velocity extrapolation, volume correction and the
// marching-cubes surface, at 64^3 and 128^3, with 2 workers.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "core/task_system.h"
#include "fluid/mac_grid.h"
#include "fluid/surface/level_set_redistance.h"
#include "fluid/surface/liquid_volume.h"
#include "fluid/surface/marching_cubes.h"
#include "fluid/surface/velocity_extrapolation.h"

namespace vp::bench {
namespace {

constexpr int kWorkers = 2;

struct DamBreak {
  MacGrid grid;
  FaceFractionField fractions;
  std::vector<double> phi;
};

DamBreak makeDamBreak(int n) {
  DamBreak d;
  MacGridSpec spec;
  spec.h = 1.0 / n;
  spec.nx = spec.ny = spec.nz = n;
  std::array<DomainSide, 6> walls;
  walls.fill(DomainSide::Wall);
  initMacGrid(spec, walls, &d.grid);
  initFaceFractionField(spec, &d.fractions);
  d.phi.resize(static_cast<size_t>(d.grid.cellCount()));
  const Eigen::Vector3d blockHigh(0.4, 0.6, 1.0), dropCentre(0.7, 0.7, 0.5);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d x = d.grid.cellCentre(i, j, k);
        const Eigen::Vector3d outside = (x - blockHigh).cwiseMax(0.0);
        const double block = outside.norm() + std::min((x - blockHigh).maxCoeff(), 0.0);
        d.phi[d.grid.cellIndex(i, j, k)] = std::min(block, (x - dropCentre).norm() - 0.12);
      }
  return d;
}

void BM_LiquidRedistance(benchmark::State& state) {
  DamBreak d = makeDamBreak(static_cast<int>(state.range(0)));
  auto tasks = TaskSystem::create(TaskHooks{}, kWorkers);
  RedistanceWorkspace ws;
  RedistanceStats stats;
  const std::vector<double> initial = d.phi;
  for (auto _ : state) {
    state.PauseTiming();
    d.phi = initial;
    state.ResumeTiming();
    redistanceLevelSet(*tasks, d.grid.spec, d.phi.data(), RedistanceSettings{}, ws, &stats);
  }
  state.counters["band_cells"] = double(stats.bandCells);
  state.counters["sweeps"] = stats.sweeps;
}
BENCHMARK(BM_LiquidRedistance)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LiquidExtrapolation(benchmark::State& state) {
  DamBreak d = makeDamBreak(static_cast<int>(state.range(0)));
  auto tasks = TaskSystem::create(TaskHooks{}, kWorkers);
  VelocityExtrapolationState ws;
  for (auto _ : state) extrapolateVelocity(*tasks, d.grid, d.fractions, d.phi.data(), {4, false}, ws);
}
BENCHMARK(BM_LiquidExtrapolation)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LiquidVolumeCorrection(benchmark::State& state) {
  DamBreak d = makeDamBreak(static_cast<int>(state.range(0)));
  auto tasks = TaskSystem::create(TaskHooks{}, kWorkers);
  const double target = liquidVolume(*tasks, d.grid.spec, d.phi.data(), nullptr);
  VolumeCorrectionResult result;
  for (auto _ : state) {
    // Lose a 0.05 h shell each time, as a drifting step would, and correct it.
    for (double& p : d.phi) p += 0.05 * d.grid.spec.h;
    correctLiquidVolume(*tasks, d.grid.spec, d.phi.data(), nullptr, target, VolumeCorrectionSettings{}, &result);
  }
  state.counters["newton_iterations"] = result.iterations;
}
BENCHMARK(BM_LiquidVolumeCorrection)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LiquidSurfaceMesh(benchmark::State& state) {
  DamBreak d = makeDamBreak(static_cast<int>(state.range(0)));
  auto tasks = TaskSystem::create(TaskHooks{}, kWorkers);
  MarchingCubesWorkspace ws;
  SurfaceMesh mesh;
  Array<Eigen::Vector3d> normals;
  for (auto _ : state) extractLiquidSurface(*tasks, d.grid.spec, d.phi.data(), &mesh, &normals, ws);
  state.counters["triangles"] = double(mesh.triangles.size());
}
BENCHMARK(BM_LiquidSurfaceMesh)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace vp::bench

// BM_PressureSolve/{mic_pcg,voxel_mgpcg,cutcell_mgpcg}/{scene}/{N}: the fluid pressure solve
// on N^3 cut-cell scenes (tests/unit/fluid_pressure_scenes.h), from p = 0 to a relative residual
// of 1e-6, and the memory bandwidth its kernels reach. Scenes: smoke_sphere, tank_plate_sphere
// (open-top tank, no free surface) and liquid_tank (the same tank filled to 0.61 with a free
// surface). cutcell_mgpcg_jacobi is the cut-cell
// multigrid with the damped Jacobi smoother instead of red-black Gauss-Seidel.
//
// Counters
//   ms             the CG solve to 1e-6 (preconditioner already built)
//   setup_ms       building the preconditioner (MIC(0) factors or the multigrid levels)
//   rebuild_ms     building it again into the same buffers (median of 3): what a fluid step
//                  pays when its operator changed, since its state keeps the buffers
//   operator_build_ms  building the fine operator (buildCutCellPoisson) into buffers already
//                  sized (median of 3), which a fluid step also pays then
//   iters          CG iterations
//   gbps           the CG's operator L p (applyCutCellPoisson, the same for every solver):
//                  bytes moved / time per application. The kernels stream only the span of
//                  each grid row from its first to its last fluid cell (poisson_rows.h) and
//                  write 0 to the rest, so the byte model is (every array streamed from memory
//                  once; neighbour values hit the cache) per span cell: p read 8, L p written 8,
//                  diagonal 8, three face-coupling arrays 3 x 8: 48 bytes; per cell outside the
//                  spans: the 8 bytes of the 0 written
//   mg_operator_gbps  the multigrid's own operator kernel, the residual b - L x on level 0
//                  (multigrid only), in the V-cycle's single precision: per span cell x 4,
//                  b 4, diagonal 4, couplings 12, r written 4: 28 bytes; 4 outside
//   smoother_gbps  one fused red-black Gauss-Seidel sweep on level 0 (multigrid only, single
//                  precision): one pass streaming x (read and written back, 8), b 4,
//                  diagonal 4, couplings 12: 28 bytes per span cell, nothing outside (a sweep
//                  that does not start from zero leaves those cells alone)
//   vcycle_per_matvec  one application of the preconditioner (a V-cycle, multigrid only) over
//                  one application of the fine operator L p above, both medians of 5 in the
//                  same iteration: what a CG iteration pays for its preconditioner, in units of
//                  its own operator (a well-built V-cycle costs 4 to 6)
//   vcycle_ms, matvec_ms  the two times themselves
//   update_ms      liquid_tank, cut-cell multigrid only: the fine operator built again after the
//                  surface moved a tenth of a cell, recording its changed rows, and the
//                  multigrid updated where they reach (poisson_multigrid.h), what a liquid's
//                  projection pays for its setup; tracked_rebuild_ms: the same builds with the
//                  multigrid rebuilt instead
//   triad_gbps     STREAM triad a = b + s c over 3 arrays of 64 MiB each (far beyond the
//                  last-level cache), 24 bytes per element, on the same task system, measured
//                  in the same run
// Each timing is the median of a few repeats inside one benchmark iteration; the benchmark
// repeats itself (3 times, aggregates only) for medians across runs of a noisy machine.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <utility>

#include "../unit/fluid_pressure_scenes.h"
#include "core/parallel_for.h"
#include "fluid/pressure/multigrid_smoother.h"
#include "fluid/pressure/poisson_multigrid.h"
#include "memory_bandwidth.h"

namespace vp::bench {
namespace {

using testscene::PressureScene;
using testscene::PressureSceneKind;
using testscene::SceneSolver;

constexpr double kTolerance = 1e-6;
constexpr int kMaxIterations = 2000;
constexpr double kOperatorBytesPerCell = 48.0;
constexpr double kResidualBytesPerCell = 28.0;
constexpr double kSweepBytesPerCell = 28.0;
constexpr double kClearedBytesPerCell = 8.0;
constexpr double kClearedFloatBytesPerCell = 4.0;

// Cells inside the rows' fluid spans (CutCellPoisson::rowSpan).
double spanCells(const CutCellPoisson& op) {
  double sum = 0.0;
  for (size_t row = 0; 2 * row < op.rowSpan.size(); ++row) sum += op.rowSpan[2 * row + 1] - op.rowSpan[2 * row];
  return op.rowSpan.empty() ? static_cast<double>(op.diagonal.size()) : sum;
}

TaskSystem& benchTasks() {
  static std::unique_ptr<TaskSystem> tasks =
      TaskSystem::create(TaskHooks{}, std::max(1, static_cast<int>(std::thread::hardware_concurrency())));
  return *tasks;
}

// Scenes are built once per (kind, N) and shared by the three solvers: face fractions of the
// 192^3 scenes take longer than some solves.
const PressureScene* scene(PressureSceneKind kind, int n) {
  static std::map<std::pair<int, int>, std::unique_ptr<PressureScene>> cache;
  auto& slot = cache[{static_cast<int>(kind), n}];
  if (!slot) {
    slot = std::make_unique<PressureScene>();
    if (testscene::makePressureScene(benchTasks(), kind, n, slot.get()) != Status::Ok) slot.reset();
  }
  return slot.get();
}

// What a liquid's projection pays when its surface has moved: the level set shifted by
// kSurfaceShift cells (up, then back), the fine operator built with its changed rows raised and
// the multigrid updated (median of 4); and the same builds when the multigrid is rebuilt.
std::pair<double, double> trackedBuilds(TaskSystem& tasks, const PressureScene& s, MultigridSettings settings) {
  constexpr double kSurfaceShift = 0.1;
  settings.coarsening = MultigridCoarsening::CutCell;
  std::vector<double> phi[2] = {s.liquidPhi, s.liquidPhi};
  for (double& v : phi[1]) v -= kSurfaceShift * s.grid.spec.h;
  CutCellPoisson fine;
  ChangedRows changed;
  PoissonMultigrid mg;
  int which = 0;
  auto build = [&](bool update) {
    SlabPasses passes(tasks);
    appendBuildCutCellPoisson(s.grid, s.fractions, &fine, phi[which].data(), &passes, &changed);
    appendBuildPoissonMultigrid(fine, s.grid.sides, settings, &mg, &passes, update ? &changed : nullptr);
    passes.runAll();
    which = 1 - which;
  };
  build(true);
  const double update = medianSeconds(4, [&] { build(true); });
  const double rebuild = medianSeconds(4, [&] { build(false); });
  return {update, rebuild};
}

void BM_PressureSolve(benchmark::State& state, PressureSolver which, PoissonSmoother smoother,
                      PressureSceneKind kind) {
  const int n = static_cast<int>(state.range(0));
  const PressureScene* built = scene(kind, n);
  if (built == nullptr) {
    state.SkipWithError(lastError());
    return;
  }
  const PressureScene& s = *built;
  TaskSystem& tasks = benchTasks();
  SceneSolver solver;
  solver.kind = which;
  solver.multigrid.smoother = smoother;
  std::vector<double> p;
  const double cells = static_cast<double>(s.rhs.size());
  const double inSpans = spanCells(s.poisson), outside = cells - inSpans;
  for (auto _ : state) {
    const double setup = medianSeconds(1, [&] {
      if (solver.prepare(tasks, s) != Status::Ok) state.SkipWithError(lastError());
    });
    const double rebuild = medianSeconds(3, [&] { (void)solver.prepare(tasks, s); });
    CutCellPoisson fine;
    const double* phi = s.liquidPhi.empty() ? nullptr : s.liquidPhi.data();
    (void)buildCutCellPoisson(tasks, s.grid, s.fractions, &fine, phi);
    const double operatorBuild =
        medianSeconds(3, [&] { (void)buildCutCellPoisson(tasks, s.grid, s.fractions, &fine, phi); });
    CgResult result;
    const double solve = medianSeconds(1, [&] { result = solver.solve(tasks, s, kTolerance, kMaxIterations, &p); });
    if (!result.converged) state.SkipWithError("pressure solve did not converge");
    state.counters["ms"] = 1e3 * solve;
    state.counters["setup_ms"] = 1e3 * setup;
    state.counters["rebuild_ms"] = 1e3 * rebuild;
    state.counters["operator_build_ms"] = 1e3 * operatorBuild;
    state.counters["iters"] = result.iterations;
    std::vector<double> out(p.size());
    const double apply = medianSeconds(5, [&] { applyCutCellPoisson(tasks, s.poisson, p.data(), out.data()); });
    state.counters["gbps"] = (kOperatorBytesPerCell * inSpans + kClearedBytesPerCell * outside) / apply / 1e9;
    if (which != PressureSolver::Mic0Pcg) {
      const PoissonCoefficients<float>& level0 = solver.mg.single.front();
      const std::vector<float> b(s.rhs.begin(), s.rhs.end()), x(p.begin(), p.end());
      std::vector<float> r(b.size());
      const double residual = medianSeconds(5, [&] { computeResidual(tasks, level0, b.data(), x.data(), r.data()); });
      state.counters["mg_operator_gbps"] =
          (kResidualBytesPerCell * inSpans + kClearedFloatBytesPerCell * outside) / residual / 1e9;
      const double sweep = medianSeconds(5, [&] { smoothRedBlack(tasks, level0, b.data(), r.data(), false); });
      state.counters["smoother_gbps"] = kSweepBytesPerCell * inSpans / sweep / 1e9;
      std::vector<double> z(p.size());
      const double vcycle =
          medianSeconds(5, [&] { applyPoissonMultigrid(tasks, s.poisson, solver.mg, s.rhs.data(), z.data()); });
      state.counters["vcycle_per_matvec"] = vcycle / apply;
      state.counters["vcycle_ms"] = 1e3 * vcycle;
      state.counters["matvec_ms"] = 1e3 * apply;
    }
    if (which == PressureSolver::CutCellMgpcg && !s.liquidPhi.empty()) {
      const std::pair<double, double> tracked = trackedBuilds(tasks, s, solver.multigrid);
      state.counters["update_ms"] = 1e3 * tracked.first;
      state.counters["tracked_rebuild_ms"] = 1e3 * tracked.second;
    }
    state.counters["triad_gbps"] = triadGbps(tasks);
  }
}

void registerAll() {
  struct Variant {
    PressureSolver solver;
    PoissonSmoother smoother;
    const char* name;
  };
  const Variant variants[] = {
      {PressureSolver::Mic0Pcg, PoissonSmoother::RedBlackGaussSeidel, "mic_pcg"},
      {PressureSolver::VoxelMgpcg, PoissonSmoother::RedBlackGaussSeidel, "voxel_mgpcg"},
      {PressureSolver::CutCellMgpcg, PoissonSmoother::RedBlackGaussSeidel, "cutcell_mgpcg"},
      {PressureSolver::CutCellMgpcg, PoissonSmoother::DampedJacobi, "cutcell_mgpcg_jacobi"},
  };
  for (PressureSceneKind kind :
       {PressureSceneKind::SmokeSphere, PressureSceneKind::TankPlateSphere, PressureSceneKind::LiquidTank})
    for (const Variant& v : variants)
      for (int n : {64, 128, 192}) {
        const PressureSolver which = v.solver;
        const std::string label = std::string("BM_PressureSolve/") + v.name + "/" + testscene::sceneName(kind);
        auto* b = benchmark::RegisterBenchmark(label.c_str(), BM_PressureSolve, which, v.smoother, kind);
        // MIC(0)-PCG at 192^3 takes about a minute per solve: one repetition there.
        const int repetitions = (which == PressureSolver::Mic0Pcg && n > 128) ? 1 : 3;
        b->Arg(n)->Iterations(1)->Repetitions(repetitions)->ReportAggregatesOnly(repetitions > 1)->Unit(
            benchmark::kMillisecond)->UseRealTime();
      }
}

const bool kRegistered = (registerAll(), true);

}  // namespace
}  // namespace vp::bench

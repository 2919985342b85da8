// One implicit-step linear solve of cubic elements, to relative residual 1e-6, three ways:
//   BM_DeformSolve/pcg/cubic       CG with block-Jacobi (the baseline of issue 6)
//   BM_DeformSolve/pmg_pcg/cubic   CG with the p-multigrid V-cycle (3 -> 2 -> 1, Chebyshev)
//   BM_DeformSolve/pmg/cubic       the V-cycle alone as a solver (Richardson)
//   BM_DeformSolve/amg_pcg/cubic   CG with the aggregation multigrid on the cubic matrix
// and variants of the cycle (BM_DeformSolve/pmg_pcg_<variant>/cubic) for the choices made in
// linalg/p_multigrid.h; the p-multigrid's coarse operators are the default re-discretized
// ones, _galerkin variants take Galerkin products. The system: the shared 4 x 1 x 1 m beam
// (beam_mesh.h) at 24x6x6 cells = 5184 cubic tets, E = 1e8, ν = 0.3, ρ = 1000, x = 0 clamped,
// the backward-Euler matrix of a 1/60 s step (M + h β K + h² K, β = 0.01), right-hand side
// the step's gravity impulse, started from zero, 2 worker threads. Time = preconditioner
// setup for this matrix (the coarse operators — re-discretized levels assembled from the
// step's gradient pairs, or the Galerkin products —, smoothers, the coarsest aggregation
// multigrid; the block-Jacobi inverses) + the solve; the one-off symbolic build (at actor
// creation) is the counter build_ms. Counters: iters, setup_ms, solve_ms, residual.
//
// Measured on the 2-core dev machine in one run (random interleaving, load 1.2-1.3), medians
// of 5: pcg 2275 ms (598 it), pmg_pcg 381 ms (16 it; 58 ms of it setup), pmg_pcg_galerkin
// 446 ms (16 it; 90 ms setup), pmg 969 ms (42 cycles), pmg_galerkin 1031 ms, amg_pcg 644 ms
// (57 it): pmg_pcg 6.0x faster than pcg, the standalone cycle 2.3x, aggregation multigrid
// alone 3.5x. (Earlier, under load 6-7: pcg 4372 ms, Galerkin pmg_pcg 960 ms, 4.6x.)
// The iteration counts of the cycle's variants are in docs/choices.md (p-multigrid).
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <chrono>
#include <string>

#include "beam_mesh.h"
#include "deform_beam_desc.h"
#include "core/budget_clock.h"
#include "core/task_system.h"
#include "deform/degree_hierarchy.h"
#include "deform/degree_level_assembly.h"
#include "deform/deformable_body.h"
#include "linalg/p_multigrid.h"
#include "linalg/richardson_iteration.h"

namespace vp::bench {
namespace {

using Mat3R = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct CubicBeamSystem {
  std::unique_ptr<DeformableBody> body;
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  std::vector<double> rhs, filters;
  double massScale = 1.0;  // of the step matrix, for re-discretized coarse levels
  bool ok = false;

  explicit CubicBeamSystem(int degree) {
    BeamCells cells;
    if (!beamCellsForTetCount(5184, &cells)) return;
    const BeamMesh beam = makeBeamMesh(cells.x, cells.y, cells.z, 4.0, 1.0, 1.0);
    DeformableDesc desc = beamDeformableDesc(beam, degree);
    desc.solver.preconditioner = Preconditioner::BlockJacobi;  // the step only assembles the matrix
    desc.solver.maxIterations = 1;
    if (!vp::ok(DeformableBody::create(std::move(desc), &body))) return;
    body->setPinned(beam.fixedVertices.data(), static_cast<int64_t>(beam.fixedVertices.size()), true);
    DeformableStepInput in;
    in.dt = 1.0 / 60.0;
    in.tasks = tasks.get();
    ActorStats stats;
    body->step(in, &stats);  // at rest: the matrix of the rest configuration
    massScale = 1.0 + in.dt * body->desc().material.massDamping;
    const int32_t n = body->nodeCount();
    rhs.assign(3 * static_cast<size_t>(n), 0.0);
    filters.assign(9 * static_cast<size_t>(n), 0.0);
    for (int32_t i = 0; i < n; ++i) {
      if (body->pinned(i)) continue;
      rhs[3 * i + 1] = -in.dt * body->nodeMasses()[i] * 9.81;
      filters[9 * i] = filters[9 * i + 4] = filters[9 * i + 8] = 1.0;
    }
    ok = true;
  }

  LinearSystem system(std::function<void(const double*, double*)> precondition) const {
    LinearSystem s;
    s.size = 3 * static_cast<int64_t>(body->nodeCount());
    s.apply = [this](const double* x, double* y) { body->stepMatrix().multiply(*tasks, x, y); };
    s.precondition = std::move(precondition);
    s.filter = [this](double* v) {
      for (int32_t i = 0; i < body->nodeCount(); ++i)
        if (body->pinned(i)) v[3 * i] = v[3 * i + 1] = v[3 * i + 2] = 0.0;
    };
    return s;
  }
};

const CubicBeamSystem& cubicSystem() {
  static const CubicBeamSystem system(3);
  return system;
}

enum class Method { Pcg, AmgPcg, PmgPcg, Pmg };

void report(benchmark::State& state, double setupMs, double solveMs, const CgResult& result) {
  state.SetIterationTime((setupMs + solveMs) / 1000.0);
  state.counters["iters"] = result.iterations;
  state.counters["setup_ms"] = setupMs;
  state.counters["solve_ms"] = solveMs;
  state.counters["residual"] = result.relativeResidual;
  if (!result.converged) state.SkipWithError("did not reach 1e-6");
}

void runSolve(benchmark::State& state, Method method, std::vector<int> degrees, PMultigridSettings settings,
              PMultigridCoarseOperator coarseOperator) {
  const CubicBeamSystem& sys = cubicSystem();
  if (!sys.ok) return state.SkipWithError("cubic beam setup failed");
  const BlockSparseMatrix<double>& A = sys.body->stepMatrix();
  const CgSettings cg{1e-6, 100000};
  const int64_t n = 3 * static_cast<int64_t>(A.blockRows);
  state.counters["blocks"] = static_cast<double>(A.blockCount());
  PMultigrid mg;
  std::vector<DegreeLevelAssembly> rediscretized;
  AggregationMultigrid amg;
  if (method == Method::AmgPcg) amg.build(A);
  if (method == Method::PmgPcg || method == Method::Pmg) {
    const auto start = Clock::now();
    DegreeHierarchy h;
    if (!ok(buildDegreeHierarchy(degrees, sys.body->elementNodes().data(), sys.body->elementCount(),
                                 sys.body->nodeCount(), &h)))
      return state.SkipWithError("hierarchy failed");
    std::vector<BlockSparseMatrix<double>*> coarse;
    if (coarseOperator == PMultigridCoarseOperator::Rediscretized) {
      rediscretized.resize(h.levels.size() - 1);
      for (size_t l = 1; l < h.levels.size(); ++l) {
        rediscretized[l - 1].build(h.levels[l], h.levels[0].degree, sys.body->restVolumes().data(),
                                   sys.body->elementCount(), sys.body->desc().material.density);
        coarse.push_back(&rediscretized[l - 1].matrix());
      }
    }
    mg.build(A, std::move(h.prolongations), settings, std::move(coarse));
    state.counters["build_ms"] = msSince(start);
    for (int l = 1; l < mg.levelCount(); ++l)
      state.counters["blocks_level" + std::to_string(l)] = static_cast<double>(mg.levelMatrix(l).blockCount());
  }
  std::vector<double> blockInverse(9 * static_cast<size_t>(A.blockRows));
  CgWorkspace work;
  for (auto _ : state) {
    std::vector<double> x(static_cast<size_t>(n), 0.0);
    auto start = Clock::now();
    if (method == Method::Pcg) {
      for (int32_t i = 0; i < A.blockRows; ++i)
        Eigen::Map<Mat3R>{&blockInverse[9 * i]} =
            Eigen::Map<const Mat3R>(&A.values[9 * static_cast<int64_t>(A.diagonal[i])]).inverse();
    } else if (method == Method::AmgPcg) {
      amg.update(*sys.tasks, A, sys.body->positions().data(), sys.filters.data());
    } else {
      for (DegreeLevelAssembly& level : rediscretized)
        level.assemble(*sys.tasks, sys.body->elementGradientPairs().data(), sys.massScale);
      mg.update(*sys.tasks, A, sys.body->positions().data(), sys.filters.data());
    }
    const double setupMs = msSince(start);
    start = Clock::now();
    CgResult result;
    if (method == Method::Pcg) {
      const LinearSystem s = sys.system([&](const double* r, double* z) {
        for (int32_t i = 0; i < A.blockRows; ++i)
          Eigen::Map<Eigen::Vector3d>(z + 3 * i) =
              Eigen::Map<const Mat3R>(&blockInverse[9 * i]) * Eigen::Map<const Eigen::Vector3d>(r + 3 * i);
      });
      result = solveConjugateGradient(*sys.tasks, s, sys.rhs.data(), x.data(), cg, Deadline(), work);
    } else if (method == Method::AmgPcg) {
      const LinearSystem s = sys.system([&](const double* r, double* z) { amg.apply(*sys.tasks, r, z); });
      result = solveConjugateGradient(*sys.tasks, s, sys.rhs.data(), x.data(), cg, Deadline(), work);
    } else {
      const LinearSystem s = sys.system([&](const double* r, double* z) { mg.apply(*sys.tasks, r, z); });
      result = method == Method::PmgPcg
                   ? solveConjugateGradient(*sys.tasks, s, sys.rhs.data(), x.data(), cg, Deadline(), work)
                   : solveRichardson(*sys.tasks, s, sys.rhs.data(), x.data(), cg, Deadline(), work);
    }
    report(state, setupMs, msSince(start), result);
  }
}

void registerSolve(const std::string& name, Method method, std::vector<int> degrees, PMultigridSettings settings,
                   PMultigridCoarseOperator coarseOperator = DeformableSolverSettings{}.pMultigridCoarseOperator) {
  benchmark::RegisterBenchmark(("BM_DeformSolve/" + name + "/cubic").c_str(),
                               [=](benchmark::State& state) { runSolve(state, method, degrees, settings, coarseOperator); })
      ->Unit(benchmark::kMillisecond)
      ->UseManualTime()
      ->Iterations(1)
      ->Repetitions(5);
}

PMultigridSettings with(PMultigridSmoother smoother, int sweeps, int coarseCycles = 1) {
  PMultigridSettings s;
  s.smoother = smoother;
  s.sweeps = sweeps;
  s.coarseCycles = coarseCycles;
  return s;
}

const bool registered = [] {
  const PMultigridSettings defaults;
  registerSolve("pcg", Method::Pcg, {}, defaults);
  registerSolve("pmg_pcg", Method::PmgPcg, {3, 2, 1}, defaults);
  registerSolve("pmg", Method::Pmg, {3, 2, 1}, defaults);
  // Galerkin coarse operators instead of the default re-discretized ones.
  const auto galerkin = PMultigridCoarseOperator::Galerkin;
  registerSolve("pmg_pcg_galerkin", Method::PmgPcg, {3, 2, 1}, defaults, galerkin);
  registerSolve("pmg_galerkin", Method::Pmg, {3, 2, 1}, defaults, galerkin);
  registerSolve("pmg_pcg_3to1_galerkin", Method::PmgPcg, {3, 1}, defaults, galerkin);
  // What Auto picked for cubic elements before p-multigrid: aggregation multigrid directly.
  registerSolve("amg_pcg", Method::AmgPcg, {}, defaults);
  // The choices behind the defaults.
  registerSolve("pmg_pcg_3to1", Method::PmgPcg, {3, 1}, defaults);
  registerSolve("pmg_pcg_jacobi2_coarse8", Method::PmgPcg, {3, 2, 1}, with(PMultigridSmoother::DampedJacobi, 2, 8));
  registerSolve("pmg_pcg_chebyshev3_coarse8", Method::PmgPcg, {3, 2, 1}, with(PMultigridSmoother::Chebyshev, 3, 8));
  for (int coarse : {1, 2, 4, 8, 16}) {
    if (coarse != defaults.coarseCycles)
      registerSolve("pmg_pcg_coarse" + std::to_string(coarse), Method::PmgPcg, {3, 2, 1},
                    with(PMultigridSmoother::Chebyshev, 2, coarse));
    registerSolve("pmg_pcg_chebyshev1_coarse" + std::to_string(coarse), Method::PmgPcg, {3, 2, 1},
                  with(PMultigridSmoother::Chebyshev, 1, coarse));
    registerSolve("pmg_pcg_jacobi1_coarse" + std::to_string(coarse), Method::PmgPcg, {3, 2, 1},
                  with(PMultigridSmoother::DampedJacobi, 1, coarse));
  }
  return true;
}();

}  // namespace
}  // namespace vp::bench

// p-multigrid's two kinds of coarse operators under contacts: a soft cubic cube (0.8 m, 5x5x5
// cells = 750 cubic tets, 4.4K nodes, E = 1e6, ν = 0.3) dropped tilted onto a ground plane
// (μ = 0.5): it lands on a corner, tips over onto a face and settles, so contacts appear,
// stick, slide, release and cover part of a face or all of it. 120 steps of 1/60 s at the
// actor's default solver settings (tolerance 1e-3, warm-started), 2 threads.
//   BM_DeformContact/galerkin        coarse operators P̃ᵀAP̃ (constrained Galerkin products)
//   BM_DeformContact/rediscretized   assembled at each degree (deform/degree_level_assembly.h)
// Counters per step: cg_iters, assemble_ms (matrix and preconditioner setup), solve_ms,
// contacts; final_y (the centroid's height at the end: both must settle alike);
// process_cpu_s (both threads: with other programs on the cores, wall time alone says little).
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>

#include "geometry/box_tet_mesh.h"
#include "ground_world.h"
#include "world.h"

namespace vp::bench {
namespace {

void runContact(benchmark::State& state, PMultigridCoarseOperator coarseOperator) {
  for (auto _ : state) {
    std::unique_ptr<World> world = worldOnGround();
    if (world == nullptr) return state.SkipWithError("world on the ground");
    DeformableDesc d;
    d.degree = 3;
    d.mesh = makeBoxTetMesh({5, 5, 5}, Vec3::Constant(0.8), Vec3::Constant(-0.4));
    d.pose.position = Vec3(0, 0.9, 0);
    d.pose.rotation = Quat(Eigen::AngleAxisd(0.6, Vec3(0, 0, 1))) * Quat(Eigen::AngleAxisd(0.35, Vec3(1, 0, 0)));
    d.material.youngsModulus = 1e6;
    d.material.friction = 0.5;
    d.solver.preconditioner = Preconditioner::PMultigrid;
    d.solver.pMultigridCoarseOperator = coarseOperator;
    DeformableHandle cube;
    if (!ok(world->createDeformable(std::move(d), &cube))) return state.SkipWithError("cube");
    const DeformableBody& body = *world->deformable(cube);
    constexpr int kSteps = 120;
    double iterations = 0.0, assembleMs = 0.0, solveMs = 0.0, contacts = 0.0;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpuStart = std::clock();
    for (int step = 0; step < kSteps; ++step) {
      if (!ok(world->step(1.0 / 60.0))) return state.SkipWithError("step");
      const ActorStats& stats = world->lastStats().actors.at(1);
      iterations += stats.phase(Phase::Solve).iterations;
      assembleMs += stats.phase(Phase::Assemble).ms;
      solveMs += stats.phase(Phase::Solve).ms;
      contacts += static_cast<double>(body.contacts().size());
    }
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    state.counters["process_cpu_s"] = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
    double y = 0.0;
    for (int32_t i = 0; i < body.nodeCount(); ++i) y += body.positions()[3 * i + 1];
    state.counters["cg_iters"] = iterations / kSteps;
    state.counters["assemble_ms"] = assembleMs / kSteps;
    state.counters["solve_ms"] = solveMs / kSteps;
    state.counters["contacts"] = contacts / kSteps;
    state.counters["final_y"] = y / body.nodeCount();
    state.counters["nodes"] = body.nodeCount();
  }
}

void BM_DeformContactGalerkin(benchmark::State& state) { runContact(state, PMultigridCoarseOperator::Galerkin); }
void BM_DeformContactRediscretized(benchmark::State& state) {
  runContact(state, PMultigridCoarseOperator::Rediscretized);
}
BENCHMARK(BM_DeformContactGalerkin)->Name("BM_DeformContact/galerkin")->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(1)->Repetitions(3);
BENCHMARK(BM_DeformContactRediscretized)->Name("BM_DeformContact/rediscretized")->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(1)->Repetitions(3);

}  // namespace
}  // namespace vp::bench

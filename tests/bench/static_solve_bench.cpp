// BM_SolveStatic/{beam,plate}/{1,2,3}: the static solve (deform/static_equilibrium.h) of a
// cantilever clamped at x = 0, to a relative residual of 1e-4 with the body's default linear
// solver settings (CG to 1e-3, so each Newton step is inexact; its iteration cap is the static
// solve's, not the per-frame solverMaxIterations).
// - beam: 4 x 1 x 1 m, 16 x 4 x 4 cubes, E = 1e8 Pa, under its own weight;
// - plate: 1 x 0.01 x 0.2 m (a hundredth as thick as long), 20 x 1 x 4 cubes, E = 2e9 Pa, a
//   0.1 N load on its free end and no gravity.
// Counters: newton_iterations (pseudo-time steps, accepted or not) and tip_drop_mm.
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <vector>

#include "beam_mesh.h"
#include "deform/static_equilibrium.h"

namespace vp::bench {
namespace {

struct Cantilever {
  BeamMesh mesh;
  double youngsModulus, tipLoad;
  Vec3 gravity;
};

Cantilever cantilever(bool plate) {
  if (plate) return {makeBeamMesh(20, 1, 4, 1.0, 0.01, 0.2), 2e9, 0.1, Vec3::Zero()};
  return {makeBeamMesh(16, 4, 4, 4.0, 1.0, 1.0), 1e8, 0.0, Vec3(0, -9.81, 0)};
}

void BM_SolveStatic(benchmark::State& state) {
  const bool plate = state.range(0) != 0;
  const int degree = static_cast<int>(state.range(1));
  const Cantilever c = cantilever(plate);
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  StaticSolveResult result;
  double tipDrop = 0.0;
  for (auto _ : state) {
    DeformableDesc desc;
    desc.degree = degree;
    desc.mesh = toTetMesh(c.mesh);
    desc.material.youngsModulus = c.youngsModulus;
    std::unique_ptr<DeformableBody> body;
    if (!ok(DeformableBody::create(desc, &body))) return state.SkipWithError(lastError());
    body->setPinned(c.mesh.fixedVertices.data(), static_cast<int64_t>(c.mesh.fixedVertices.size()), true);
    if (c.tipLoad != 0.0) body->applyForce(c.mesh.tipVertex, Vec3(0, -c.tipLoad, 0));
    DeformableStepInput in;
    in.tasks = tasks.get();
    in.gravity = c.gravity;
    const auto start = std::chrono::steady_clock::now();
    const Status s = solveStaticEquilibrium(*body, in, 200, 1e-4, &result);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!ok(s)) return state.SkipWithError(lastError());
    tipDrop = c.mesh.vertices[3 * c.mesh.tipVertex + 1] - body->positions()[3 * c.mesh.tipVertex + 1];
  }
  state.counters["newton_iterations"] = result.iterations;
  state.counters["tip_drop_mm"] = 1e3 * tipDrop;
}
BENCHMARK(BM_SolveStatic)
    ->ArgNames({"plate", "degree"})
    ->ArgsProduct({{0, 1}, {1, 2, 3}})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(1)
    ->Repetitions(3);

}  // namespace
}  // namespace vp::bench

#include "beam_run.h"

#include <chrono>
#include <ctime>
#include <utility>

#include "beam_mesh.h"
#include "core/task_system.h"
#include "deform/deformable_body.h"
#include "deform_beam_desc.h"

namespace vp::bench {

BeamRun runBeam(int64_t tets, double tolerance, int maxIterations, int workers, int degree,
                Preconditioner preconditioner, PMultigridCoarseOperator coarse, bool onDevice) {
  BeamRun run;
  BeamCells cells;
  if (!beamCellsNearTetCount(tets, &cells)) return run;
  const BeamMesh beam = makeBeamMesh(cells.x, cells.y, cells.z, 4.0, 1.0, 1.0);
  run.tets = beam.tetCount();
  if (!findBeamMeshDefect(beam, 4.0).empty()) return run;
  DeformableDesc desc = beamDeformableDesc(beam, degree);
  desc.solver.tolerance = tolerance;
  desc.solver.maxIterations = maxIterations;
  desc.solver.preconditioner = preconditioner;
  desc.solver.pMultigridCoarseOperator = coarse;
  std::unique_ptr<DeformableBody> body;
  if (!ok(DeformableBody::create(std::move(desc), &body))) return run;
  run.nodes = body->nodeCount();
  if (onDevice && !ok(body->setSolveOnDevice(true))) return run;
  // Pinning the clamped face's vertices also pins its edge/face control points (degree > 1).
  body->setPinned(beam.fixedVertices.data(), static_cast<int64_t>(beam.fixedVertices.size()), true);
  auto tasks = TaskSystem::create(TaskHooks{}, workers);
  DeformableStepInput in;
  in.dt = 1.0 / 60.0;
  in.gravity = Vec3(0, -9.81, 0);
  in.tasks = tasks.get();
  const double y0 = body->positions()[3 * beam.tipVertex + 1];
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  int iterations = 0;
  for (int step = 0; step < 60; ++step) {
    ActorStats stats;
    body->step(in, &stats);
    iterations += stats.phase(Phase::Solve).iterations;
    for (int p = 0; p < kPhaseCount; ++p) run.phaseMs[p] += stats.phases[p].ms / 60.0;
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.processCpuSeconds = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  run.tipDy = body->positions()[3 * beam.tipVertex + 1] - y0;
  run.cgIterations = iterations / 60.0;
  run.onDevice = body->solvesOnDevice();
  run.ok = true;
  return run;
}

void reportBeamRun(benchmark::State& state, const BeamRun& run) {
  state.SetIterationTime(run.seconds);
  state.counters["hz"] = 60.0 / run.seconds;
  state.counters["cg_iters"] = run.cgIterations;
  state.counters["tip_dy"] = run.tipDy;
  state.counters["tets"] = static_cast<double>(run.tets);
  state.counters["nodes"] = run.nodes;
  state.counters["process_cpu_s"] = run.processCpuSeconds;
  const std::pair<Phase, const char*> phases[] = {
      {Phase::Corotate, "corotate_ms"}, {Phase::Assemble, "assemble_ms"}, {Phase::Solve, "solve_ms"}, {Phase::Embed, "embed_ms"}};
  for (const auto& [phase, name] : phases) state.counters[name] = run.phaseMs[static_cast<int>(phase)];
}

}  // namespace vp::bench

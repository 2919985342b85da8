// One run of the issues' cantilever beam as a deformable (the shared mesh, beam_mesh.h; x = 0
// clamped, gravity, dt = 1/60 s, 60 steps), timed, and its Google Benchmark counters: hz,
// cg_iters, tip_dy, tets, nodes, process_cpu_s and the per-step phase times. Shared by the CPU
// benchmarks (deform_beam_bench.cpp) and the GPU ones (tests/gpu/).
#pragma once

#include <benchmark/benchmark.h>

#include <cstdint>

#include "deform/deformable_desc.h"
#include "step_stats.h"

namespace vp::bench {

struct BeamRun {
  double seconds = 0.0, tipDy = 0.0, cgIterations = 0.0;
  int64_t tets = 0;
  int32_t nodes = 0;
  double phaseMs[kPhaseCount] = {};  // per step
  double processCpuSeconds = 0.0;    // all threads: with other programs competing for the
                                     // cores, wall time alone says little
  bool onDevice = false;             // the solves ran on the CUDA device
  bool ok = false;
};

// tets: the beam nearest that count (beamCellsNearTetCount). onDevice: the implicit solves on
// the CUDA device (the run fails where none is usable).
BeamRun runBeam(int64_t tets, double tolerance, int maxIterations, int workers, int degree = 1,
                Preconditioner preconditioner = Preconditioner::Auto,
                PMultigridCoarseOperator coarse = DeformableSolverSettings{}.pMultigridCoarseOperator,
                bool onDevice = false);

void reportBeamRun(benchmark::State& state, const BeamRun& run);

}  // namespace vp::bench

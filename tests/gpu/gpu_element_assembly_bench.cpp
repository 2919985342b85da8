// Corotation and stiffness assembly of the cantilever beam (tests/bench/beam_mesh.h) after 20
// steps of sag, linear tets at 12288 and 98304 elements, quadratic ones at 13000 (13056):
//   BM_GpuElementAssembly/{12288,98304,13000q}   gpu::DeviceElementAssembly, a thread per element
//       then a thread per node row, device events over a batch of assemblies (warm-started
//       rotations, as in a step);
//   BM_CpuElementAssembly/{12288,98304,13000q}   the same kernel bodies in DeformableBody's two
//       parallel passes (elasticForces), 2 worker threads, the same run.
// Counter: ms per assembly. Figures: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "beam_mesh.h"
#include "deform/deformable_body.h"
#include "deform_beam_desc.h"
#include "gpu_kernels/device_element_assembly.h"
#include "gpu_kernels/device_query.h"

namespace vp::gpu_test {
namespace {

struct SaggedBeam {
  std::unique_ptr<DeformableBody> body;
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
};

bool makeSaggedBeam(int tets, int degree, SaggedBeam* out) {
  bench::BeamCells cells;
  if (!bench::beamCellsForTetCount(tets, &cells)) return false;
  const bench::BeamMesh beam = bench::makeBeamMesh(cells.x, cells.y, cells.z, 4.0, 1.0, 1.0);
  if (DeformableBody::create(bench::beamDeformableDesc(beam, degree), &out->body) != Status::Ok) return false;
  out->body->setPinned(beam.fixedVertices.data(), static_cast<int64_t>(beam.fixedVertices.size()), true);
  DeformableStepInput in;
  in.dt = 1.0 / 60.0;
  in.gravity = Vec3(0, -9.81, 0);
  in.tasks = out->tasks.get();
  for (int step = 0; step < 20; ++step) {
    ActorStats stats;
    out->body->step(in, &stats);
  }
  return true;
}

void BM_GpuElementAssembly(benchmark::State& state, int tets, int degree) {
  if (gpu::cudaDeviceCount() == 0) return state.SkipWithError("no CUDA device");
  SaggedBeam beam;
  if (!makeSaggedBeam(tets, degree, &beam)) return state.SkipWithError("beam not made");
  const DeformableBody& body = *beam.body;
  std::string error;
  auto device = gpu::DeviceElementAssembly::create(body.elementAssemblyView(), &error);
  if (!device) return state.SkipWithError(error.c_str());
  std::vector<double> quat(body.elementRotations().begin(), body.elementRotations().end());
  std::vector<double> values(9 * static_cast<size_t>(body.stepMatrix().rowStart[body.nodeCount()]));
  std::vector<double> force(3 * static_cast<size_t>(body.nodeCount()));
  if (!device->assemble(body.positions().data(), quat.data(), 1.0, values.data(), force.data(), &error))
    return state.SkipWithError(error.c_str());
  double ms = 0.0;
  for (auto _ : state) {
    if (!device->timeAssemble(10, 1.0, &ms, &error)) return state.SkipWithError(error.c_str());
    state.SetIterationTime(ms / 1000.0);
  }
  state.counters["ms"] = ms;
}

void BM_CpuElementAssembly(benchmark::State& state, int tets, int degree) {
  SaggedBeam beam;
  if (!makeSaggedBeam(tets, degree, &beam)) return state.SkipWithError("beam not made");
  Array<double> force;
  for (auto _ : state) beam.body->elasticForces(*beam.tasks, &force);
}

const bool registered = [] {
  const struct {
    int tets, degree;
    const char* name;
  } cases[] = {{12288, 1, "12288"}, {98304, 1, "98304"}, {13000, 2, "13000q"}};
  for (const auto& c : cases) {
    const int tets = c.tets, degree = c.degree;
    benchmark::RegisterBenchmark((std::string("BM_GpuElementAssembly/") + c.name).c_str(),
                                 [tets, degree](benchmark::State& s) { BM_GpuElementAssembly(s, tets, degree); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(10)
        ->Repetitions(3);
    benchmark::RegisterBenchmark((std::string("BM_CpuElementAssembly/") + c.name).c_str(),
                                 [tets, degree](benchmark::State& s) { BM_CpuElementAssembly(s, tets, degree); })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(5)
        ->Repetitions(3);
  }
  return true;
}();

}  // namespace
}  // namespace vp::gpu_test

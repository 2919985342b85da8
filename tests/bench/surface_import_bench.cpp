// Cost of importing a surface file isolated from the host (geometry/isolated_import.h: assimp
// in a forked child, the triangles back over a pipe) against importing it in-process, on the
// default scene's duck (/usr/share/assimp/models/Collada/duck.dae).
//   BM_SurfaceImport/0   in-process (importSurfaceMeshWithAssimp)
//   BM_SurfaceImport/1   isolated (loadSurfaceMesh)
// Counters: vertices, triangles. The difference is the isolation's cost (fork, pipe, reap).
#include <benchmark/benchmark.h>

#include "geometry/surface_mesh.h"

namespace vp::bench {
namespace {

constexpr const char* kDuck = "/usr/share/assimp/models/Collada/duck.dae";

void BM_SurfaceImport(benchmark::State& state) {
  const bool isolated = state.range(0) == 1;
  SurfaceMesh mesh;
  for (auto _ : state) {
    const Status s = isolated ? loadSurfaceMesh(kDuck, &mesh) : importSurfaceMeshWithAssimp(kDuck, &mesh);
    if (!ok(s)) return state.SkipWithError(lastError());
    benchmark::DoNotOptimize(mesh.vertices.data());
  }
  state.counters["vertices"] = double(mesh.vertices.size());
  state.counters["triangles"] = double(mesh.triangles.size());
}
BENCHMARK(BM_SurfaceImport)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace
}  // namespace vp::bench

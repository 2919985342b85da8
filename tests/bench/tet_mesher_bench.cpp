// BM_TetMesher/{duck,star}/{16,32}[/graded]: isosurface stuffing (geometry/isosurface_stuffing.h)
// of a closed surface at 16 and 32 lattice cells along its longest axis, on the uniform lattice
// or (graded) on the octree-graded one with kBenchGrading levels of coarsening inside.
// - duck: the default scene's model (/usr/share/assimp/models/Collada/duck.dae);
// - star: the thin-armed star of the unit tests (a ball with six capsule arms, 0.24 across,
//   reaching 1 from the centre; tests/unit/geometry_test_shapes.h).
// Counters: ms (the mesher alone, the surface already loaded), tets, volume_error (tets'
// volume over the surface's, less 1), min_dihedral and max_dihedral (degrees).
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>

#include "../unit/geometry_test_shapes.h"
#include "geometry/isosurface_stuffing.h"
#include "geometry/mesh_quality.h"

namespace vp::bench {
namespace {

constexpr const char* kDuck = "/usr/share/assimp/models/Collada/duck.dae";
constexpr int kBenchGrading = 3;

void runStuffing(benchmark::State& state, const std::string& shape, int resolution, int grading) {
  SurfaceMesh surface;
  if (shape == "star") surface = test::star(5, 0.35, 0.12, 1.0);
  else if (!ok(loadSurfaceMesh(kDuck, &surface))) return state.SkipWithError(lastError());
  TetMesh mesh;
  double ms = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const Status s = tetrahedralizeByStuffing(surface, resolution, &mesh, nullptr, StuffingBoundary::KeepVolume, grading);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!ok(s)) return state.SkipWithError(lastError());
    state.SetIterationTime(seconds);
    ms = 1e3 * seconds;
  }
  const TetMeshQuality q = tetMeshQuality(mesh, surface);
  state.counters["ms"] = ms;
  state.counters["tets"] = static_cast<double>(mesh.tets.size());
  state.counters["volume_error"] = q.tetVolume / q.surfaceVolume - 1.0;
  state.counters["min_dihedral"] = q.minDihedralDegrees;
  state.counters["max_dihedral"] = q.maxDihedralDegrees;
}

const bool registered = [] {
  for (const char* shape : {"duck", "star"})
    for (int resolution : {16, 32})
      for (int grading : {0, kBenchGrading})
        benchmark::RegisterBenchmark(("BM_TetMesher/" + std::string(shape) + "/" + std::to_string(resolution) +
                                      (grading > 0 ? "/graded" : ""))
                                         .c_str(),
                                     [=](benchmark::State& state) { runStuffing(state, shape, resolution, grading); })
            ->Unit(benchmark::kMillisecond)
            ->UseManualTime()
            ->Iterations(1)
            ->Repetitions(3);
  return true;
}();

}  // namespace
}  // namespace vp::bench

// Jellies stacked on a ground plane (deform/pair_contacts.h): N cubes of 0.2 m (4x4x4 cells,
// 384 linear tets, 125 nodes each; E = 1e5, density 1000), put down 1 cm apart, fall onto
// each other and settle; 120 steps of 1/60 s, 2 threads, no frame budget.
//   BM_DeformableStack/N   N = 2, 8
// Counters per step: detection_ms (finding the pair contacts: surface refits and BVH
// queries, World::findDeformablePairContacts), deformable_ms (the deformables' steps: their
// stats' totalMs summed), detection_share = detection_ms / (detection_ms + deformable_ms),
// the share of the deformable stage the issue bounds at 20%; pairs (contacts found); and at the
// end top_y (the top cube's centroid) and max_speed (the fastest node of any cube).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "geometry/box_tet_mesh.h"
#include "ground_world.h"
#include "world.h"

namespace vp::bench {
namespace {

constexpr double kSize = 0.2, kGap = 0.01;

void BM_DeformableStack(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  for (auto _ : state) {
    std::unique_ptr<World> world = worldOnGround();
    if (world == nullptr) return state.SkipWithError("world on the ground");
    std::vector<DeformableHandle> cubes(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
      DeformableDesc d;
      d.mesh = makeBoxTetMesh({4, 4, 4}, Vec3::Constant(kSize), Vec3(-0.5 * kSize, i * (kSize + kGap), -0.5 * kSize));
      d.material.youngsModulus = 1e5;
      if (!ok(world->createDeformable(std::move(d), &cubes[static_cast<size_t>(i)])))
        return state.SkipWithError("cube");
    }
    constexpr int kSteps = 120;
    double detectionMs = 0.0, deformableMs = 0.0, pairs = 0.0;
    const auto start = std::chrono::steady_clock::now();
    for (int step = 0; step < kSteps; ++step) {
      if (!ok(world->step(1.0 / 60.0))) return state.SkipWithError("step");
      const StepStats& stats = world->lastStats();
      detectionMs += stats.deformableContactMs;
      for (const ActorStats& a : stats.actors)
        if (a.kind == ActorKind::Deformable) deformableMs += a.totalMs;
      pairs += static_cast<double>(stats.deformablePairContacts);
    }
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    double maxSpeed = 0.0;
    for (DeformableHandle h : cubes) {
      const Array<double>& v = world->deformable(h)->velocities();
      for (size_t i = 0; i + 2 < v.size(); i += 3) maxSpeed = std::max(maxSpeed, Vec3(v[i], v[i + 1], v[i + 2]).norm());
    }
    const DeformableBody& top = *world->deformable(cubes.back());
    double y = 0.0;
    for (int32_t i = 0; i < top.nodeCount(); ++i) y += top.positions()[3 * i + 1];
    state.counters["detection_ms"] = detectionMs / kSteps;
    state.counters["deformable_ms"] = deformableMs / kSteps;
    state.counters["detection_share"] = detectionMs / (detectionMs + deformableMs);
    state.counters["pairs"] = pairs / kSteps;
    state.counters["top_y"] = y / top.nodeCount();
    state.counters["max_speed"] = maxSpeed;
  }
}
BENCHMARK(BM_DeformableStack)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(1)->Repetitions(3);

}  // namespace
}  // namespace vp::bench

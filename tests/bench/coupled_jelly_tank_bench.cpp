// A jelly floating in a liquid tank stirred by a paddle (issue 15's coupling benchmark): the
// cost of the two-way coupling against the fluid step it rides on.
//   BM_CoupledJellyTank/N   an N^3 liquid tank of 1 m (half full, open top), a kinematic paddle
//                           turning at 1.5 rad/s, a 0.3 m jelly (10^3 cells, 6000 linear tets,
//                           density 500) floating beside it; 2 threads, no frame budget
// Two worlds are stepped side by side, frame by frame: the coupled one, and a twin whose jelly
// the fluid does not see (collision filters; the jelly sinks to the floor). Counters, medians
// over the measured frames (kWarmFrames first frames left out):
//   fluid_ms           the tank's step in the coupled world (its stats' totalMs)
//   fluid_ms_uncoupled the same in the twin
//   fractions_ms       the coupled tank's Fractions phase (paddle and jelly surface), and
//   fractions_ms_uncoupled the twin's (paddle only)
//   coupling_ms        fluid_ms - fluid_ms_uncoupled: what the jelly adds to the fluid's step
//                      (its surface's fractions, the loads on its nodes, and the flow it stirs)
//   coupling_share     coupling_ms / fluid_ms (the issue bounds it at 25%)
//   coupling_phase_ms  the coupled tank's Coupling phase: the jelly's fractions and the loads on
//                      its nodes, as the issue counts the coupling; coupling_phase_share of fluid_ms
//   immersion_ms       the jelly's own step in the coupled world less the twin's (the loads'
//                      stabilization and whatever the different motion costs)
//   advect_ms, pressure_ms, surface_ms (and _uncoupled): the tank's other phases, where the rest
//                      of coupling_ms goes (pressure_ms: the projections, which the jelly's
//                      moving boundary makes take more iterations)
//   pressure_iters (and _uncoupled): the tank's pressure iterations per step, all sub-steps
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "geometry/box_tet_mesh.h"
#include "ground_world.h"
#include "world.h"

namespace vp::bench {
namespace {

constexpr int kWarmFrames = 5, kMeasuredFrames = 20;
constexpr uint32_t kUnseenCategory = 2;  // the twin's jelly: the tank's filter leaves it out

struct Tank {
  std::unique_ptr<World> world;
  FluidHandle fluid{};
  DeformableHandle jelly{};
};

bool makeTank(int n, bool coupled, Tank* t) {
  t->world = worldOnGround();
  if (t->world == nullptr) return false;
  FluidDesc f;
  f.kind = FluidKind::Liquid;
  f.grid.h = 1.0 / n;
  f.grid.nx = f.grid.ny = f.grid.nz = n;
  f.sides[3] = DomainSide::Open;
  f.filter.mask = ~kUnseenCategory;
  FluidShape water;
  water.type = FluidShape::Type::Box;
  water.centre = Vec3(0.5, 0.25, 0.5);
  water.halfExtents = Vec3(0.5, 0.25, 0.5);
  f.initialLiquid.push_back(water);
  if (!ok(t->world->createFluid(std::move(f), &t->fluid))) return false;
  ColliderDesc paddle;
  paddle.bodyType = BodyType::Kinematic;
  paddle.shape.type = ShapeType::Box;
  paddle.shape.halfExtents = Vec3(0.2, 0.15, 0.02);
  paddle.pose.position = Vec3(0.3, 0.25, 0.3);
  paddle.angularVelocity = Vec3(0.0, 1.5, 0.0);
  ColliderHandle paddleHandle;
  if (!ok(t->world->createCollider(paddle, &paddleHandle))) return false;
  DeformableDesc d;
  d.mesh = makeBoxTetMesh({10, 10, 10}, Vec3::Constant(0.3), Vec3(0.55, 0.42, 0.55));
  d.material.youngsModulus = 1e5;
  d.material.density = 500.0;
  if (!coupled) d.filter.category = kUnseenCategory;
  return ok(t->world->createDeformable(std::move(d), &t->jelly));
}

const ActorStats* actorStats(const World& world, ActorKind kind) {
  for (const ActorStats& a : world.lastStats().actors)
    if (a.kind == kind) return &a;
  return nullptr;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void BM_CoupledJellyTank(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) {
    Tank coupled, twin;
    if (!makeTank(n, true, &coupled) || !makeTank(n, false, &twin)) return state.SkipWithError(lastError());
    std::vector<double> fluid[2], fractions[2], jelly[2], advect[2], pressure[2], surface[2], iterations[2],
        coupling[2];
    for (int frame = 0; frame < kWarmFrames + kMeasuredFrames; ++frame) {
      Tank* tanks[2] = {&coupled, &twin};
      for (int w = 0; w < 2; ++w) {
        if (!ok(tanks[w]->world->step(1.0 / 60.0))) return state.SkipWithError(lastError());
        const ActorStats* f = actorStats(*tanks[w]->world, ActorKind::Fluid);
        const ActorStats* d = actorStats(*tanks[w]->world, ActorKind::Deformable);
        if (f == nullptr || d == nullptr) return state.SkipWithError("actor stats");
        if (frame < kWarmFrames) continue;
        fluid[w].push_back(f->totalMs);
        fractions[w].push_back(f->phase(Phase::Fractions).ms);
        advect[w].push_back(f->phase(Phase::Advect).ms);
        pressure[w].push_back(f->phase(Phase::Pressure).ms);
        surface[w].push_back(f->phase(Phase::Surface).ms);
        iterations[w].push_back(f->phase(Phase::Pressure).iterations);
        coupling[w].push_back(f->phase(Phase::Coupling).ms);
        jelly[w].push_back(d->totalMs);
      }
    }
    const double fluidMs = median(fluid[0]), uncoupledMs = median(fluid[1]);
    state.counters["fluid_ms"] = fluidMs;
    state.counters["fluid_ms_uncoupled"] = uncoupledMs;
    state.counters["fractions_ms"] = median(fractions[0]);
    state.counters["fractions_ms_uncoupled"] = median(fractions[1]);
    state.counters["coupling_ms"] = fluidMs - uncoupledMs;
    state.counters["coupling_share"] = (fluidMs - uncoupledMs) / fluidMs;
    state.counters["immersion_ms"] = median(jelly[0]) - median(jelly[1]);
    state.counters["coupling_phase_ms"] = median(coupling[0]);
    state.counters["coupling_phase_share"] = median(coupling[0]) / fluidMs;
    const char* suffix[2] = {"", "_uncoupled"};
    for (int w = 0; w < 2; ++w) {
      state.counters[std::string("advect_ms") + suffix[w]] = median(advect[w]);
      state.counters[std::string("pressure_ms") + suffix[w]] = median(pressure[w]);
      state.counters[std::string("surface_ms") + suffix[w]] = median(surface[w]);
      state.counters[std::string("pressure_iters") + suffix[w]] = median(iterations[w]);
    }
  }
}
BENCHMARK(BM_CoupledJellyTank)->Arg(64)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vp::bench

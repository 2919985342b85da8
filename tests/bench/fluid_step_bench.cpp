// Whole fluid steps through the World (fractions, advection, forces, pressure), unbudgeted:
// BM_FluidSmokeStep/N  hot smoke rising from an emitter past a sphere (radius 0.2 of the
//                      domain), open top, N^3 cells.
// BM_FluidLiquidStep/N dam break: a column of water (0.4 of the tank wide, 0.8 high) falls
//                      around a box obstacle into a closed tank of N^3 cells.
// Counters: hz (steps per second of wall time), pressure_ms and pressure_iters per step, and
// the other phases' ms per step (surface_ms: redistancing, volume correction, extrapolation);
// bytes_per_cell: the bytes allocated after the warm-up steps less before the fluid was
// created, over its cells (what the fluid keeps: fields, fractions, workspaces, solver
// levels); triad_gbps: STREAM triad on as many workers as the world's, in the same run;
// substeps: CFL sub-steps per step; advect_gbps: the bytes advection must move at least over
// advect_ms: per sub-step every advected field read once and written once over the whole grid
// (3 velocity components and, for smoke, density and temperature, for a liquid its level set:
// 16 bytes per cell and field). The liquid skips air faces far from its surface, so its
// figure counts bytes it did not move and reads high; smoke advects everything.
#include <benchmark/benchmark.h>

#include "memory_bandwidth.h"
#include "world.h"

namespace vp {
namespace {

constexpr int kWorkers = 2;
constexpr double kBytesPerCellAndField = 16.0;  // one double read, one written

std::unique_ptr<World> makeWorld() {
  WorldConfig config;
  config.workerCount = kWorkers;
  config.frameBudgetMs = 0.0;  // measure the full cost; budget behaviour has its own benchmark
  std::unique_ptr<World> world;
  World::create(config, &world);
  return world;
}

Status addStaticSphere(World& world, const Vec3& centre, double radius) {
  ColliderDesc sphere;
  sphere.bodyType = BodyType::Static;
  sphere.shape.type = ShapeType::Sphere;
  sphere.shape.radius = radius;
  sphere.pose.position = centre;
  ColliderHandle h;
  return world.createCollider(sphere, &h);
}

// Warm-up steps let the flow develop (an empty domain solves in 0 iterations), then every
// timed iteration is one world step. allocatedBefore: bench::allocatedBytes() before the fluid
// was created; scalarFields: the cell-centred fields it advects.
void runFluidSteps(benchmark::State& state, World& world, int warmup, double cells, double allocatedBefore,
                   int scalarFields) {
  for (int s = 0; s < warmup; ++s) world.step(1.0 / 60.0);
  const double fluidBytes = bench::allocatedBytes() - allocatedBefore;
  double pressureMs = 0.0, iterations = 0.0, advectMs = 0.0, forcesMs = 0.0, fractionsMs = 0.0, surfaceMs = 0.0,
         substeps = 0.0;
  for (auto _ : state) {
    world.step(1.0 / 60.0);
    for (const ActorStats& a : world.lastStats().actors)
      if (a.kind == ActorKind::Fluid) {
        pressureMs += a.phase(Phase::Pressure).ms;
        iterations += a.phase(Phase::Pressure).iterations;
        advectMs += a.phase(Phase::Advect).ms;
        forcesMs += a.phase(Phase::Forces).ms;
        fractionsMs += a.phase(Phase::Fractions).ms;
        surfaceMs += a.phase(Phase::Surface).ms;
        substeps += a.substeps;
      }
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["hz"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["pressure_ms"] = pressureMs / n;
  state.counters["pressure_iters"] = iterations / n;
  state.counters["advect_ms"] = advectMs / n;
  state.counters["forces_ms"] = forcesMs / n;
  state.counters["fractions_ms"] = fractionsMs / n;
  state.counters["surface_ms"] = surfaceMs / n;
  state.counters["substeps"] = substeps / n;
  const double advectedBytes = substeps * cells * (3 + scalarFields) * kBytesPerCellAndField;
  state.counters["advect_gbps"] = advectMs > 0.0 ? advectedBytes / (advectMs * 1e-3) / 1e9 : 0.0;
  state.counters["bytes_per_cell"] = fluidBytes / cells;
  auto tasks = TaskSystem::create(TaskHooks{}, kWorkers);
  state.counters["triad_gbps"] = bench::triadGbps(*tasks);
}

void BM_FluidSmokeStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto world = makeWorld();
  if (!ok(addStaticSphere(*world, Vec3(0.5, 0.55, 0.5), 0.2))) return state.SkipWithError(lastError());
  FluidDesc d;
  d.kind = FluidKind::Smoke;
  d.grid.h = 1.0 / n;
  d.grid.nx = d.grid.ny = d.grid.nz = n;
  d.sides[3] = DomainSide::Open;
  d.density = 1.2;
  FluidEmitter e;
  e.shape.type = FluidShape::Type::Sphere;
  e.shape.centre = Vec3(0.5, 0.12, 0.5);
  e.shape.radius = 0.08;
  e.velocity = Vec3(0, 0.5, 0);
  e.densityRate = 1.0;
  e.temperature = 2.0;
  d.emitters.push_back(e);
  FluidHandle h;
  const double before = bench::allocatedBytes();
  if (!ok(world->createFluid(d, &h))) return state.SkipWithError(lastError());
  runFluidSteps(state, *world, n <= 64 ? 30 : 10, double(n) * n * n, before, 2);
}
BENCHMARK(BM_FluidSmokeStep)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

void BM_FluidLiquidStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  auto world = makeWorld();
  ColliderDesc obstacle;
  obstacle.bodyType = BodyType::Static;
  obstacle.shape.type = ShapeType::Box;
  obstacle.shape.halfExtents = Vec3(0.08, 0.15, 0.2);
  obstacle.pose.position = Vec3(0.65, 0.15, 0.5);
  ColliderHandle c;
  if (!ok(world->createCollider(obstacle, &c))) return state.SkipWithError(lastError());
  FluidDesc d;
  d.kind = FluidKind::Liquid;
  d.grid.h = 1.0 / n;
  d.grid.nx = d.grid.ny = d.grid.nz = n;
  FluidShape column;
  column.type = FluidShape::Type::Box;
  column.centre = Vec3(0.2, 0.4, 0.5);
  column.halfExtents = Vec3(0.2, 0.4, 0.5);
  d.initialLiquid.push_back(column);
  FluidHandle h;
  const double before = bench::allocatedBytes();
  if (!ok(world->createFluid(d, &h))) return state.SkipWithError(lastError());
  runFluidSteps(state, *world, n <= 64 ? 20 : 8, double(n) * n * n, before, 1);
}
BENCHMARK(BM_FluidLiquidStep)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

}  // namespace
}  // namespace vp

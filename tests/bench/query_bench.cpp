// Scene queries against deformables (the render surface), on the default scene after 30
// unbudgeted frames (the jelly and the duck deformed, at rest on the ground and in the tank):
// BM_RaycastDeformables/bvh    rays through vp::raycast (the surface BVH, refit when moved)
// BM_RaycastDeformables/brute  the same rays as vp::raycast cast them before the BVH: per
//                              deformable its surface's box (computed per ray), and when
//                              the ray meets it, every triangle: the reference to beat
// Each iteration casts a 32 x 32 grid of downward rays over the deformables' boxes; counters:
// rays_per_s, triangles (all deformables' render triangles), hits (of the 1024 rays, on the
// state after the 30 frames, counted both ways before timing: the benchmark fails if they
// differ). Only the first query after a step refits the tree: a step (untimed) is taken
// every iteration so the figure includes one refit per 1024 rays.
#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>

#include "default_scene.h"
#include "query/triangle_queries.h"
#include "query/world_query.h"

namespace {

using namespace vp;

std::vector<Ray> downwardRays(World& world) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (DeformableHandle h : world.deformableHandles())
    for (const Vec3& p : world.deformable(h)->renderPositions()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  std::vector<Ray> rays;
  constexpr int kSide = 32;
  for (int i = 0; i < kSide; ++i)
    for (int k = 0; k < kSide; ++k) {
      Ray r;
      r.origin = Vec3(lo.x() + (hi.x() - lo.x()) * (i + 0.5) / kSide, hi.y() + 1.0,
                      lo.z() + (hi.z() - lo.z()) * (k + 0.5) / kSide);
      r.direction = -Vec3::UnitY();
      r.maxDistance = hi.y() - lo.y() + 2.0;
      rays.push_back(r);
    }
  return rays;
}

bool rayMeetsBox(const Ray& ray, const Vec3& lo, const Vec3& hi) {
  double enter = 0.0, exit = ray.maxDistance;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(ray.direction[k]) < 1e-300) {
      if (ray.origin[k] < lo[k] || ray.origin[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - ray.origin[k]) / ray.direction[k], b = (hi[k] - ray.origin[k]) / ray.direction[k];
    if (a > b) std::swap(a, b);
    enter = std::max(enter, a);
    exit = std::min(exit, b);
    if (enter > exit) return false;
  }
  return true;
}

// The reference: per deformable its box, then every triangle, nearest hit kept.
bool bruteForceHit(World& world, const Ray& ray) {
  double nearest = ray.maxDistance;
  bool hit = false;
  for (DeformableHandle h : world.deformableHandles()) {
    const DeformableBody& body = *world.deformable(h);
    const Array<Vec3>& x = body.renderPositions();
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : x) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    if (!rayMeetsBox(ray, lo, hi)) continue;
    for (const auto& tri : body.renderMeshRest().triangles) {
      TriangleRayHit t;
      if (rayHitsTriangle(ray.origin, ray.direction, nearest, x[tri[0]], x[tri[1]], x[tri[2]], &t))
        nearest = t.distance, hit = true;
    }
  }
  return hit;
}

void BM_RaycastDeformables(benchmark::State& state) {
  const bool brute = state.range(0) == 1;
  auto world = bench::defaultSceneWorld();
  if (!world) return state.SkipWithError(lastError());
  world->setFrameBudget(0.0);
  for (int i = 0; i < 30; ++i) world->step(1.0 / 60.0);
  int64_t triangles = 0;
  for (DeformableHandle h : world->deformableHandles())
    triangles += static_cast<int64_t>(world->deformable(h)->renderMeshRest().triangles.size());
  const std::vector<Ray> rays = downwardRays(*world);
  QueryFilter filter;
  filter.kinds = static_cast<uint32_t>(QueryKind::Deformable);
  std::vector<QueryHit> hits;
  auto cast = [&](bool useBrute) {
    int64_t count = 0;
    for (const Ray& r : rays) {
      if (useBrute) {
        count += bruteForceHit(*world, r);
      } else {
        raycast(*world, r, filter, true, &hits);
        count += !hits.empty();
      }
    }
    return count;
  };
  const int64_t hitCount = cast(false);
  if (hitCount != cast(true)) return state.SkipWithError("the BVH and the brute force disagree on the hits");
  int64_t raysCast = 0;
  for (auto _ : state) {
    state.PauseTiming();
    world->step(1.0 / 60.0);  // the surfaces move: the BVH refits on the first ray
    state.ResumeTiming();
    benchmark::DoNotOptimize(cast(brute));
    raysCast += static_cast<int64_t>(rays.size());
  }
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(raysCast), benchmark::Counter::kIsRate);
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["hits"] = static_cast<double>(hitCount);
}

}  // namespace

BENCHMARK(BM_RaycastDeformables)->ArgName("brute")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

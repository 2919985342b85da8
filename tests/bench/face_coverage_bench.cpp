// Cost of a face's covered fraction where two colliders cut it, the case that made the default
// scene's tank spend whole frames on face fractions once its buoy drifted against the paddle.
//   BM_FaceCoverageUnion/0   a sphere and a rotated box (exact: inclusion-exclusion)
//   BM_FaceCoverageUnion/1   a cylinder and a rotated box (the bounded quadtree)
// Counters: faces (cut by both solids), ns_per_face.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <vector>

#include "collide/face_coverage.h"

namespace vp::bench {
namespace {

constexpr double kCellSize = 1.0 / 12.0;  // the default scene's fluid cell size

void BM_FaceCoverageUnion(benchmark::State& state) {
  ColliderShape round;
  round.kind = state.range(0) == 0 ? ShapeKind::Sphere : ShapeKind::Cylinder;
  round.radius = 0.2;
  round.halfHeight = 0.2;
  round.translation = Eigen::Vector3d(0.55, 0.0, 0.0);
  ColliderShape paddle;  // the default scene's paddle, turned about y
  paddle.kind = ShapeKind::Box;
  paddle.halfExtents = Eigen::Vector3d(0.6, 0.12, 0.05);
  paddle.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  PreparedCollider a, b;
  if (!ok(prepareCollider(round, &a)) || !ok(prepareCollider(paddle, &b))) return state.SkipWithError(lastError());
  const PreparedCollider* pair[] = {&a, &b};
  std::vector<AxisFace> faces;
  for (int axis = 0; axis < 3; ++axis)
    for (int k = -12; k <= 12; ++k)
      for (int j = -12; j <= 12; ++j)
        for (int i = -12; i <= 12; ++i) {
          AxisFace f;
          f.axis = axis;
          f.h = kCellSize;
          f.centre = Eigen::Vector3d(i, j, k) * kCellSize;
          f.centre[(axis + 1) % 3] += 0.5 * kCellSize;
          f.centre[(axis + 2) % 3] += 0.5 * kCellSize;
          const double fa = coveredFraction(a, f), fb = coveredFraction(b, f);
          if (fa > 0.0 && fa < 1.0 && fb > 0.0 && fb < 1.0) faces.push_back(f);
        }
  double sink = 0.0;
  for (auto _ : state)
    for (const AxisFace& f : faces) sink += coveredFractionUnion(pair, 2, f);
  benchmark::DoNotOptimize(sink);
  state.counters["faces"] = static_cast<double>(faces.size());
  state.counters["ns_per_face"] = benchmark::Counter(static_cast<double>(faces.size()),
                                                     benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}
BENCHMARK(BM_FaceCoverageUnion)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vp::bench

// The 3x3-block matrix multiply that dominates CG, stored as float or as double, on the
// 98304-tet beam's pattern. Vectors are double in both cases; only the matrix differs.
#include <benchmark/benchmark.h>

#include <random>

#include "beam_mesh.h"
#include "core/task_system.h"
#include "linalg/block_sparse_matrix.h"

namespace vp::bench {
namespace {

template <class Scalar>
void BM_BlockSpMV(benchmark::State& state) {
  const BeamMesh beam = makeBeamMesh(64, 16, 16, 4.0, 1.0, 1.0);
  BlockSparseMatrix<Scalar> m;
  Array<int32_t> scatter;
  buildElementPattern(beam.vertexCount(), beam.tets.data(), beam.tetCount(), 4, &m, &scatter);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& v : m.values) v = static_cast<Scalar>(u(rng));
  std::vector<double> x(3 * static_cast<size_t>(m.blockRows)), y(x.size());
  for (auto& v : x) v = u(rng);
  auto tasks = TaskSystem::create(TaskHooks{}, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    m.multiply(*tasks, x.data(), y.data());
    benchmark::DoNotOptimize(y.data());
  }
  const double bytes = double(m.values.size()) * sizeof(Scalar) + double(m.columns.size()) * sizeof(int32_t) +
                       2.0 * double(x.size()) * sizeof(double);
  state.counters["gbps"] = benchmark::Counter(bytes * double(state.iterations()) / 1e9, benchmark::Counter::kIsRate);
  state.counters["blocks"] = double(m.blockCount());
}
BENCHMARK_TEMPLATE(BM_BlockSpMV, float)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_BlockSpMV, double)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace
}  // namespace vp::bench

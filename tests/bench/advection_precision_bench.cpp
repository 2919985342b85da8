// What single precision would buy advection on this CPU: the trilinear samples that are most
// of its cost, in double (what advection uses) and in float (what issue 14 asked to measure),
// through the same kernel bodies (gpu_kernels/advection_kernels.h: latticeSpan,
// trilinearCorners) and the same batch shape as runtime/fluid/advection/advection_rows.cpp:
// per batch of kTraceBatch points along a row, the stencil spans, then each corner's loads as
// a loop of their own, then the interpolation; built for AVX-512 / AVX2 / baseline and picked
// at load time like the library's loops (core/isa_clones.h).
//
// BM_AdvectionGatherPrecision/<0 double, 1 float>/N: an N^3 field sampled at every cell
// centre displaced by a smooth trace-like offset, one thread; items_per_second counts samples.
// Figures and the decision they led to: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/isa_clones.h"
#include "fluid/advection/advection_rows.h"
#include "gpu_kernels/advection_kernels.h"

namespace vp::bench {
namespace {

template <class Real>
struct GatherInputs {
  int n = 0;
  std::vector<Real> field;
  std::vector<Real> at[3];  // lattice coordinates per sample, cell order
};

template <class Real>
GatherInputs<Real> makeInputs(int n) {
  GatherInputs<Real> in;
  in.n = n;
  const int64_t cells = static_cast<int64_t>(n) * n * n;
  in.field.resize(static_cast<size_t>(cells));
  for (auto& a : in.at) a.resize(static_cast<size_t>(cells));
  for (int64_t c = 0; c < cells; ++c) {
    const double i = static_cast<double>(c % n), j = static_cast<double>((c / n) % n),
                 k = static_cast<double>(c / (static_cast<int64_t>(n) * n));
    in.field[static_cast<size_t>(c)] = static_cast<Real>(std::sin(0.1 * i) * std::cos(0.07 * j) + 0.01 * k);
    // A back-trace of up to 1.5 cells that turns with the position, as a swirling flow's does.
    in.at[0][static_cast<size_t>(c)] = static_cast<Real>(i - 1.5 * std::sin(0.05 * j));
    in.at[1][static_cast<size_t>(c)] = static_cast<Real>(j - 1.5 * std::cos(0.05 * k));
    in.at[2][static_cast<size_t>(c)] = static_cast<Real>(k - 0.7);
  }
  return in;
}

// One batch as advection_rows.cpp samples it: spans, lowest corners, corner loads, interpolation.
template <class Real>
VP_CLONE_INLINE inline Real sampleBatch(const GatherInputs<Real>& in, int64_t first, int count) {
  const int dims[3] = {in.n, in.n, in.n};
  const kernels::LatticeSteps st = kernels::latticeSteps(dims);
  int base[3][kTraceBatch];
  Real weight[3][kTraceBatch];
  for (int d = 0; d < 3; ++d) {
    const Real* g = in.at[d].data() + first;
    for (int s = 0; s < count; ++s) kernels::latticeSpan(g[s], dims[d], &base[d][s], &weight[d][s]);
  }
  int64_t index[kTraceBatch];
  for (int s = 0; s < count; ++s)
    index[s] = base[0][s] * st.stride[0] + base[1][s] * st.stride[1] + base[2][s] * st.stride[2];
  Real corners[8][kTraceBatch];
  for (int q = 0; q < 8; ++q) {
    const int64_t offset = kernels::cornerOffset(q, st.step);
    for (int s = 0; s < count; ++s) corners[q][s] = in.field[static_cast<size_t>(index[s] + offset)];
  }
  Real sum = 0;
  for (int s = 0; s < count; ++s) {
    Real c[8];
    for (int q = 0; q < 8; ++q) c[q] = corners[q][s];
    sum += kernels::trilinearCorners(c, weight[0][s], weight[1][s], weight[2][s]);
  }
  return sum;
}

template <class Real>
VP_CLONE_INLINE inline double sampleAll(const GatherInputs<Real>& in) {
  const int64_t cells = static_cast<int64_t>(in.field.size());
  double sum = 0.0;
  for (int64_t first = 0; first < cells; first += kTraceBatch)
    sum += static_cast<double>(
        sampleBatch(in, first, static_cast<int>(cells - first < kTraceBatch ? cells - first : kTraceBatch)));
  return sum;
}

VP_ISA_CLONES
double sampleAllDouble(const GatherInputs<double>& in) { return sampleAll(in); }

VP_ISA_CLONES
double sampleAllFloat(const GatherInputs<float>& in) { return sampleAll(in); }

template <class Real, class Run>
void runGather(benchmark::State& state, const Run& run) {
  const GatherInputs<Real> in = makeInputs<Real>(static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(run(in));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(in.field.size()));
}

void BM_AdvectionGatherPrecision(benchmark::State& state) {
  if (state.range(0) == 0)
    runGather<double>(state, sampleAllDouble);
  else
    runGather<float>(state, sampleAllFloat);
}
BENCHMARK(BM_AdvectionGatherPrecision)
    ->ArgsProduct({{0, 1}, {64, 128}})
    ->ArgNames({"float", "n"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vp::bench

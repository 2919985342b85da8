// What the benchmarks measure bandwidth and footprint with, in the same run as the kernels:
// the STREAM triad on a given task system, and the bytes the process has allocated.
#pragma once

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "core/parallel_for.h"

namespace vp::bench {

inline double seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The median wall time of `repeats` calls of fn.
template <class Fn>
double medianSeconds(int repeats, const Fn& fn) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const double start = seconds();
    fn();
    t.push_back(seconds() - start);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// STREAM triad a = b + s c over 3 arrays of 64 MiB each (far beyond the last-level cache), 24
// bytes per element, median of 5, in GB/s.
inline double triadGbps(TaskSystem& tasks) {
  constexpr int64_t kElements = int64_t(8) << 20;
  static std::vector<double> a(kElements), b(kElements, 1.0), c(kElements, 2.0);
  const double t = medianSeconds(5, [&] {
    parallelFor(tasks, kElements, int64_t(1) << 16, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) a[i] = b[i] + 3.0 * c[i];
    });
  });
  benchmark::DoNotOptimize(a.data());
  return 24.0 * kElements / t / 1e9;
}

// Bytes the process has allocated and not freed (glibc's mallinfo2: heap chunks in use plus
// mmapped chunks), 0 without glibc 2.33 or later. Unlike the resident size it does not keep
// what earlier benchmarks in the same process freed.
#if defined(__GLIBC__)
#define VP_BENCH_HAVE_MALLINFO2 __GLIBC_PREREQ(2, 33)
#else
#define VP_BENCH_HAVE_MALLINFO2 0
#endif

inline double allocatedBytes() {
#if VP_BENCH_HAVE_MALLINFO2
  const struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks) + static_cast<double>(info.hblkhd);
#else
  return 0.0;
#endif
}

}  // namespace vp::bench

// parallel_for / parallel_reduce over index ranges with deterministic chunking.
//
// [0, n) is cut into chunks of exactly `grain` indices (the last may be shorter). The chunk
// boundaries depend only on n and grain, never on the worker count, and a reduction sums
// per-chunk partials in chunk order, so results are bitwise identical for 1 or 64 workers.
#pragma once

#include <cstdint>
#include <vector>

#include "core/task_system.h"

namespace vp {

// body(begin, end) is called for every chunk, possibly concurrently.
template <class Body>
void parallelFor(TaskSystem& tasks, int64_t n, int64_t grain, const Body& body) {
  if (n <= 0) return;
  if (grain < 1) grain = 1;
  const int64_t chunks = (n + grain - 1) / grain;
  struct Context {
    const Body* body;
    int64_t n, grain;
  } ctx{&body, n, grain};
  auto trampoline = [](int32_t first, int32_t last, uint32_t, void* p) {
    auto* c = static_cast<Context*>(p);
    for (int64_t chunk = first; chunk < last; ++chunk) {
      int64_t begin = chunk * c->grain;
      int64_t end = begin + c->grain < c->n ? begin + c->grain : c->n;
      (*c->body)(begin, end);
    }
  };
  tasks.run(trampoline, static_cast<int32_t>(chunks), 1, &ctx);
}

// Sums partial(begin, end) over the chunks in chunk order. T needs T{} and operator+=.
template <class T, class Partial>
T parallelReduce(TaskSystem& tasks, int64_t n, int64_t grain, const Partial& partial) {
  if (n <= 0) return T{};
  if (grain < 1) grain = 1;
  const int64_t chunks = (n + grain - 1) / grain;
  std::vector<T> partials(static_cast<size_t>(chunks));
  parallelFor(tasks, chunks, 1, [&](int64_t first, int64_t last) {
    for (int64_t chunk = first; chunk < last; ++chunk) {
      int64_t begin = chunk * grain;
      partials[static_cast<size_t>(chunk)] = partial(begin, begin + grain < n ? begin + grain : n);
    }
  });
  T sum{};
  for (const T& p : partials) sum += p;
  return sum;
}

}  // namespace vp

#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/allocator.h"
#include "core/budget_clock.h"
#include "core/task_system.h"

namespace vp {

// Work as a list of passes run in bounded slices (a fluid step spread over frames,
// fluid_actor.h): the pressure projection's sliced setup and finish use it, and the whole-call
// builders run the same passes in one go, so every pass has one implementation.
//
// A pass covers `units` units (grid rows, cells) of `samplesPerUnit` samples each. A slice
// runs the units of consecutive passes in order up to a bound on samples, and at least one
// unit, so a slice exceeds the bound only when it is a single unit. A pass runs as slabs of
// units, in order, each unit once:
// * parallel pass: the units write disjoint outputs and read nothing the pass writes, so
//   where slabs are cut (and how a slab is chunked over workers, parallel_for.h) never
//   changes results;
// * serial pass: one call per slab, in order; it may carry state from slab to slab (a scan
//   in cell order), so its results are those of one whole call.
// A step is work without samples (sizing buffers, adding passes planned from what earlier
// passes built); it runs in whichever slice reaches it. Passes a step adds run right after
// it, before what followed it, so a builder's plan can read what the passes before it built.
// Sizing allocates (and zero-fills) only on a first build or a change of grid; the passes
// then write every value, so no pass clears an array first.
class SlabPasses {
 public:
  using Body = std::function<void(int64_t begin, int64_t end)>;

  SlabPasses() = default;
  explicit SlabPasses(TaskSystem& tasks) : tasks_(&tasks) {}
  // Empties the list (keeping its storage) for new work on `tasks`.
  void reset(TaskSystem& tasks);

  // body(begin, end) for chunks of `grain` units inside each slab, possibly concurrently.
  void addParallel(int64_t units, int64_t samplesPerUnit, int64_t grain, Body body);
  // body(begin, end) once per slab, in order.
  void addSerial(int64_t units, int64_t samplesPerUnit, Body body);
  // A pass that cannot be split: one unit of `samples`.
  void addWhole(int64_t samples, std::function<void()> body);
  void addStep(std::function<void()> step);

  // Runs the next slice of at most maxSamples samples (maxSamples >= 1); true when nothing
  // is left. With `stop`, the slice also ends once stop has expired: the samples then run in
  // pieces of at most maxSamples / kPiecesPerSlice, with stop read between them on the calling
  // thread. A pass's samples stand for its mean cost, and a few units can cost many times it
  // (faces a mesh cuts beside faces no solid touches): the clock bounds such a slice where
  // the count alone would not.
  bool runSlice(int64_t maxSamples, const Deadline* stop = nullptr);
  static constexpr int64_t kPiecesPerSlice = 8;
  void runAll();
  bool done() const { return next_ >= passes_.size(); }
  // Of the last runSlice: samples run and units run.
  int64_t lastSliceSamples() const { return lastSamples_; }
  int64_t lastSliceUnits() const { return lastUnits_; }

 private:
  struct Pass {
    int64_t units = 0;  // 0: a step
    int64_t samplesPerUnit = 0;
    int64_t grain = 0;  // 0: serial
    Body body;
    std::function<void()> step;
  };
  void add(Pass pass);

  TaskSystem* tasks_ = nullptr;
  Array<Pass> passes_;
  size_t next_ = 0;      // the pass running or next to run
  int64_t nextUnit_ = 0;  // its first unit not yet run
  size_t insertAt_ = 0;  // while a step runs: where the passes it adds go
  bool inStep_ = false;
  int64_t lastSamples_ = 0, lastUnits_ = 0;
};

// The sample loop of the sliced runs that keep their own pass state (the level-set upkeep):
// step(samplesLeft) does part of the work and returns the samples it did; runs it until done()
// or maxSamples are spent and returns the samples run.
template <class Done, class Step>
int64_t runSamplesUpTo(int64_t maxSamples, const Done& done, const Step& step) {
  int64_t ran = 0;
  while (!done() && ran < maxSamples) ran += step(maxSamples - ran);
  return ran;
}

}  // namespace vp

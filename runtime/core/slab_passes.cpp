#include "core/slab_passes.h"

#include <algorithm>
#include <cstddef>

#include "core/parallel_for.h"

namespace vp {

void SlabPasses::reset(TaskSystem& tasks) {
  tasks_ = &tasks;
  passes_.clear();
  next_ = 0;
  nextUnit_ = 0;
  inStep_ = false;
  lastSamples_ = lastUnits_ = 0;
}

void SlabPasses::add(Pass pass) {
  if (inStep_) passes_.insert(passes_.begin() + static_cast<std::ptrdiff_t>(insertAt_++), std::move(pass));
  else passes_.push_back(std::move(pass));
}

void SlabPasses::addParallel(int64_t units, int64_t samplesPerUnit, int64_t grain, Body body) {
  if (units <= 0) return;
  add(Pass{units, std::max<int64_t>(samplesPerUnit, 1), std::max<int64_t>(grain, 1), std::move(body), {}});
}

void SlabPasses::addSerial(int64_t units, int64_t samplesPerUnit, Body body) {
  if (units <= 0) return;
  add(Pass{units, std::max<int64_t>(samplesPerUnit, 1), 0, std::move(body), {}});
}

void SlabPasses::addWhole(int64_t samples, std::function<void()> body) {
  addSerial(1, samples, [body = std::move(body)](int64_t, int64_t) { body(); });
}

void SlabPasses::addStep(std::function<void()> step) { add(Pass{0, 0, 0, {}, std::move(step)}); }

bool SlabPasses::runSlice(int64_t maxSamples, const Deadline* stop) {
  lastSamples_ = lastUnits_ = 0;
  int64_t left = std::max<int64_t>(maxSamples, 1);
  const int64_t piece = stop ? std::max<int64_t>(left / kPiecesPerSlice, 1) : left;
  while (next_ < passes_.size()) {
    if (passes_[next_].units == 0) {
      // Moved out first: the passes it adds may move the list.
      const std::function<void()> step = std::move(passes_[next_].step);
      inStep_ = true;
      insertAt_ = next_ + 1;
      step();
      inStep_ = false;
      ++next_;
      continue;
    }
    if (left <= 0 || (stop && lastUnits_ > 0 && stop->expired())) break;
    const Pass& pass = passes_[next_];
    int64_t count = std::min(pass.units - nextUnit_, left / pass.samplesPerUnit);
    if (count == 0) {
      if (lastUnits_ > 0) break;  // the next unit starts the next slice
      count = 1;
    }
    count = std::min(count, std::max<int64_t>(piece / pass.samplesPerUnit, 1));
    const int64_t first = nextUnit_;
    if (pass.grain > 0)
      parallelFor(*tasks_, count, pass.grain,
                  [&](int64_t begin, int64_t end) { pass.body(first + begin, first + end); });
    else
      pass.body(first, first + count);
    lastSamples_ += count * pass.samplesPerUnit;
    lastUnits_ += count;
    left -= count * pass.samplesPerUnit;
    nextUnit_ += count;
    if (nextUnit_ == pass.units) {
      ++next_;
      nextUnit_ = 0;
    }
  }
  return done();
}

void SlabPasses::runAll() {
  while (!runSlice(INT64_MAX)) {
  }
}

}  // namespace vp

// How many samples a slab slice does (slab_passes.h and the fluid's sliced runs), kept near a
// target duration from the measured cost of the slices that ran: a slower or busier machine
// gets smaller slabs, so one slice stays a small part of the frame budget on any machine.
// Where slabs are cut never changes results, so neither does this.
//
// The slabs start at the floor and grow, by at most kMaxChange per piece of work, up to a
// preferred size: a first slice's cost is unknown (and a first pass over memory not touched
// yet costs several times a later one); a slice's length says how many samples fit only when
// the slice was full, and a pass smaller than one slab (a small grid) would otherwise grow
// the slabs without bound.
#pragma once

#include <cstdint>

namespace vp {

class SliceSizer {
 public:
  // Starts at min(kMinSamples, preferredSamples) and never exceeds preferredSamples (at
  // least 1).
  explicit SliceSizer(int64_t preferredSamples);

  int64_t samples() const { return samples_; }
  // A slice of slab work, run at samples(), took `ms`: one well over targetMs shrinks the
  // slabs at once (the next slice already runs smaller ones).
  void noteSlice(double ms, double targetMs);
  // At the end of a piece of work (a fluid step): grows samples() back toward the preferred
  // size when the longest slice noted since the last call was well under targetMs.
  // targetMs <= 0 (unbudgeted): nothing changes in either.
  void adapt(double targetMs);

  // The fewest samples it goes down to (unless preferred is fewer): a few hundred microseconds
  // of work on a slow machine, so a slice's fixed cost stays small.
  static constexpr int64_t kMinSamples = int64_t(1) << 10;

  // What evolves (a saved world state keeps it); restore() clamps it to the sizer's range.
  struct State {
    int64_t samples = 0;
    double longestMs = 0.0;
  };
  State state() const { return State{samples_, longestMs_}; }
  void restore(const State& s);

 private:
  void scale(double factor);
  static constexpr double kMaxChange = 2.0;

  int64_t preferred_, samples_;
  double longestMs_ = 0.0;
};

}  // namespace vp

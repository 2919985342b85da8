// How far a piece of work that may span frames (a fluid step) has got, in work units that do
// not depend on how the work is cut into slices: samples for slab work, and a fixed nominal
// amount for a slice that is not (frame_plan.h paces the step by it). Counting slices instead
// made the pace follow the slab sizes: slabs that grew four-fold made a step look four times
// as long as it was.
#pragma once

#include <cstdint>

namespace vp {

class WorkProgress {
 public:
  void begin() { done_ = 0; }
  void add(int64_t work) { done_ += work; }
  // The piece completed: its total becomes last(), and expected() follows it.
  void finish();

  // Of the piece in progress (or the last one, after finish()).
  int64_t done() const { return done_; }
  // Of the last completed piece (0 before the first).
  int64_t last() const { return last_; }
  // What a piece is expected to take (0 before the first completed): the most any recent
  // piece took, forgetting a quarter of the excess per piece, since a step's work grows with
  // its CG iterations and sub-steps (an underestimate leaves the rest to the step's last
  // frame).
  int64_t expected() const { return expected_; }
  // done() against expected(), below 1 while the piece is in progress.
  double fraction() const;

 private:
  int64_t done_ = 0, last_ = 0, expected_ = 0;
};

}  // namespace vp

// How far a piece of work that may span frames (a fluid step) has got, in work units that do
// not depend on how the work is cut into slices: samples for slab work, and a fixed nominal
// amount for a slice that is not (frame_plan.h paces the step by it). Counting slices instead
// made the pace follow the slab sizes: slabs that grew four-fold made a step look four times
// as long as it was.
//
// A piece is a head (a fluid step's face fractions and plan) and then a number of like parts
// (its sub-steps), known only once the head is done: the expectation is kept per part, so a
// step that turns out to need four sub-steps after one that needed one is expected to take
// about four times as long (an expectation kept per step left the rest of such a step to its
// last frame, over the budget).
#pragma once

#include <cstdint>

namespace vp {

class WorkProgress {
 public:
  void begin() { done_ = head_ = 0; }
  void add(int64_t work) { done_ += work; }
  // The head of the piece in progress is done, and `parts` parts (>= 1) follow: expected()
  // becomes the head's work and that many parts' worth (unchanged before any piece
  // completed). A piece that never calls it is all parts.
  void expectParts(int parts);
  // The piece completed with `parts` parts (>= 1): its total becomes last(), and the
  // expectation per part follows it.
  void finish(int parts);

  // Of the piece in progress (or the last one, after finish()).
  int64_t done() const { return done_; }
  // Of the last completed piece (0 before the first).
  int64_t last() const { return last_; }
  // What the piece is expected to take (0 before the first completed): per part, the most any
  // recent piece took, forgetting a quarter of the excess per piece, since a step's work also
  // grows with its CG iterations (an underestimate leaves the rest to the step's last frame);
  // times the parts of the piece in progress (after a finish, of the piece that completed).
  int64_t expected() const { return expected_; }
  int64_t expectedPerPart() const { return perPart_; }
  int parts() const { return static_cast<int>(parts_); }
  // done() against expected(), below 1 while the piece is in progress.
  double fraction() const;
  // What a saved copy must satisfy.
  bool valid() const;

 private:
  int64_t done_ = 0, last_ = 0, expected_ = 0, perPart_ = 0;
  int64_t head_ = 0;  // of the piece in progress, or the last (the work before its parts)
  int64_t parts_ = 1;  // 64 bits: a saved copy has no padding
};

}  // namespace vp

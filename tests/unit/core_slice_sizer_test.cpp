// Slab sizes that follow the measured slice cost toward the budget's target (slice_sizer.h).
#include <gtest/gtest.h>

#include "core/slice_sizer.h"

namespace vp {
namespace {

// Short slices for `steps` pieces of work at a target of 1 ms.
void growFor(SliceSizer& s, int steps) {
  for (int i = 0; i < steps; ++i) {
    s.noteSlice(0.1, 1.0);
    s.adapt(1.0);
  }
}

TEST(SliceSizer, StartsAtTheFloorAndDoublesPerStepUpToThePreferredSize) {
  SliceSizer s(16384);
  EXPECT_EQ(s.samples(), SliceSizer::kMinSamples);
  growFor(s, 1);
  EXPECT_EQ(s.samples(), 2 * SliceSizer::kMinSamples);  // at most doubled per step
  growFor(s, 3);
  EXPECT_EQ(s.samples(), 16384);
  growFor(s, 3);
  EXPECT_EQ(s.samples(), 16384);  // never past the preferred size
  SliceSizer small(100);  // preferred below the floor: starts and stays there
  EXPECT_EQ(small.samples(), 100);
  small.noteSlice(50.0, 1.0);
  EXPECT_EQ(small.samples(), 100);
  growFor(small, 2);
  EXPECT_EQ(small.samples(), 100);
}

TEST(SliceSizer, ALongSliceShrinksTheNextOnesAtOnceByAtMostHalf) {
  SliceSizer s(16384);
  growFor(s, 4);
  ASSERT_EQ(s.samples(), 16384);
  s.noteSlice(4.0, 2.0);  // twice the target
  EXPECT_EQ(s.samples(), 8192);
  s.noteSlice(40.0, 2.0);  // twenty times: one preempted slice must not collapse the slabs
  EXPECT_EQ(s.samples(), 4096);
  s.noteSlice(2.4, 2.0);  // within the dead band
  EXPECT_EQ(s.samples(), 4096);
}

TEST(SliceSizer, ShortSlicesGrowBackAtTheStepsEndButNotWithinTheDeadBand) {
  SliceSizer s(16384);
  growFor(s, 4);
  for (int i = 0; i < 4; ++i) s.noteSlice(8.0, 1.0);
  EXPECT_EQ(s.samples(), 1024);  // the floor
  s.adapt(1.0);  // the step that shrank them ends: nothing to grow
  EXPECT_EQ(s.samples(), 1024);
  s.noteSlice(0.25, 1.0);
  s.adapt(1.0);
  EXPECT_EQ(s.samples(), 2048);  // at most doubled per step
  s.noteSlice(0.9, 1.0);  // within the dead band: stays
  s.adapt(1.0);
  EXPECT_EQ(s.samples(), 2048);
}

TEST(SliceSizer, WithoutATargetNothingChanges) {
  SliceSizer s(4096);
  s.noteSlice(50.0, 0.0);
  s.noteSlice(0.01, 0.0);
  s.adapt(0.0);
  EXPECT_EQ(s.samples(), SliceSizer::kMinSamples);
}

}  // namespace
}  // namespace vp

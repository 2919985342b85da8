// SlabPasses' clock stop (core/slab_passes.h): a slice asked to stop runs its samples in
// pieces, reads the clock between them on the calling thread, and ends at the first piece
// boundary after the stop has expired; every unit still runs exactly once, in order, however
// the slices were cut.
#include <gtest/gtest.h>

#include <vector>

#include "../budget/tick_clock.h"
#include "core/slab_passes.h"

namespace vp {
namespace {

constexpr int64_t kUnits = 1000;

// One parallel pass of kUnits units of one sample each, counting how often each unit ran.
struct CountedPass {
  std::unique_ptr<TaskSystem> tasks = TaskSystem::create(TaskHooks{}, 2);
  std::vector<int> runs = std::vector<int>(kUnits, 0);
  SlabPasses passes{*tasks};
  CountedPass() {
    passes.addParallel(kUnits, 1, 16, [this](int64_t begin, int64_t end) {
      for (int64_t u = begin; u < end; ++u) ++runs[static_cast<size_t>(u)];
    });
  }
};

TEST(SlabPassesStop, ASliceEndsAtThePieceAfterItsStopExpires) {
  CountedPass work;
  testutil::TickClock clock;  // 0.1 ms a reading
  // The stop's own reading starts it; it has expired by the second reading after that. A
  // slice of 800 samples runs pieces of 100, reading the clock after each: 200 units.
  const Deadline stop(clock.clock(), 0.15);
  EXPECT_FALSE(work.passes.runSlice(800, &stop));
  EXPECT_EQ(work.passes.lastSliceUnits(), 2 * 800 / SlabPasses::kPiecesPerSlice);
  // Without a stop the next slice runs its whole bound; then the rest, each unit once.
  EXPECT_FALSE(work.passes.runSlice(500));
  EXPECT_EQ(work.passes.lastSliceUnits(), 500);
  EXPECT_TRUE(work.passes.runSlice(kUnits));
  for (int64_t u = 0; u < kUnits; ++u) ASSERT_EQ(work.runs[static_cast<size_t>(u)], 1) << "unit " << u;
}

TEST(SlabPassesStop, AStopThatNeverExpiresChangesNothingButThePieces) {
  CountedPass work;
  const Deadline never;  // unlimited
  EXPECT_FALSE(work.passes.runSlice(800, &never));
  EXPECT_EQ(work.passes.lastSliceUnits(), 800);
  EXPECT_EQ(work.passes.lastSliceSamples(), 800);
  EXPECT_TRUE(work.passes.runSlice(800, &never));
  for (int64_t u = 0; u < kUnits; ++u) ASSERT_EQ(work.runs[static_cast<size_t>(u)], 1) << "unit " << u;
}

TEST(SlabPassesStop, AnExpiredStopStillRunsOnePiece) {
  // A slice always makes progress: at least one piece (one unit when a unit is larger).
  CountedPass work;
  testutil::TickClock clock;
  const Deadline stop(clock.clock(), 0.01);  // expired at its first reading
  EXPECT_FALSE(work.passes.runSlice(800, &stop));
  EXPECT_EQ(work.passes.lastSliceUnits(), 800 / SlabPasses::kPiecesPerSlice);
}

}  // namespace
}  // namespace vp

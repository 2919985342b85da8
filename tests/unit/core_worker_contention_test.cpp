// When the pool's workers go off and come back (worker_contention.h), frame by frame.
#include <gtest/gtest.h>

#include "core/worker_contention.h"

namespace vp {
namespace {

using W = WorkerContention;

TEST(WorkerContention, QuietFramesKeepTheWorkersOn) {
  W w;
  for (int f = 0; f < 1000; ++f) ASSERT_TRUE(w.noteFrame(16.0, 0.3, true));  // below kMinDelayMs
  EXPECT_TRUE(w.noteFrame(16.0, 0.2 * 16.0, true));  // below kContendedFraction of the frame
  EXPECT_TRUE(w.noteFrame(16.0, -1.0, true));        // unknown: on
}

TEST(WorkerContention, AContendedFrameTurnsThemOffForAHoldThatDoublesOnEachFailedProbe) {
  W w;
  EXPECT_FALSE(w.noteFrame(16.0, 8.0, true));
  int off = 1;
  while (!w.noteFrame(16.0, 0.0, false)) ++off;
  EXPECT_EQ(off, W::kFirstHoldFrames);
  // The probe frame finds the cores still busy: twice as long off.
  EXPECT_FALSE(w.noteFrame(16.0, 8.0, true));
  off = 1;
  while (!w.noteFrame(16.0, 0.0, false)) ++off;
  EXPECT_EQ(off, 2 * W::kFirstHoldFrames);
  // Probes keep failing: the hold stops at its cap.
  for (int probe = 0; probe < 10; ++probe) {
    EXPECT_FALSE(w.noteFrame(16.0, 8.0, true));
    off = 1;
    while (!w.noteFrame(16.0, 0.0, false)) ++off;
  }
  EXPECT_EQ(off, W::kMaxHoldFrames);
}

TEST(WorkerContention, CalmFramesWithTheWorkersOnResetTheHold) {
  W w;
  for (int probe = 0; probe < 3; ++probe) {
    EXPECT_FALSE(w.noteFrame(16.0, 8.0, true));
    while (!w.noteFrame(16.0, 0.0, false)) {
    }
  }
  for (int f = 0; f < W::kCalmFrames; ++f) ASSERT_TRUE(w.noteFrame(16.0, 0.0, true));
  EXPECT_FALSE(w.noteFrame(16.0, 8.0, true));
  int off = 1;
  while (!w.noteFrame(16.0, 0.0, false)) ++off;
  EXPECT_EQ(off, W::kFirstHoldFrames);
}

}  // namespace
}  // namespace vp

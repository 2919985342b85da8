// The work a step is expected to take and how far it has got (work_progress.h).
#include <gtest/gtest.h>

#include "core/work_progress.h"

namespace vp {
namespace {

void runPiece(WorkProgress& w, int64_t total) {
  w.begin();
  w.add(total / 2);
  w.add(total - total / 2);
  w.finish();
}

TEST(WorkProgress, ExpectsTheMostARecentPieceTookForgettingAQuarterOfTheExcessPerPiece) {
  WorkProgress w;
  EXPECT_EQ(w.expected(), 0);  // unknown before the first
  runPiece(w, 1000);
  EXPECT_EQ(w.last(), 1000);
  EXPECT_EQ(w.expected(), 1000);
  runPiece(w, 600);  // a lighter piece: the expectation comes down by a quarter of the gap
  EXPECT_EQ(w.last(), 600);
  EXPECT_EQ(w.expected(), 600 + 400 * 3 / 4);
  runPiece(w, 2000);  // a heavier one: at once
  EXPECT_EQ(w.expected(), 2000);
}

TEST(WorkProgress, TheFractionStaysBelowOneWhileThePieceRuns) {
  WorkProgress w;
  runPiece(w, 1000);
  w.begin();
  EXPECT_EQ(w.fraction(), 0.0);
  w.add(250);
  EXPECT_DOUBLE_EQ(w.fraction(), 0.25);
  w.add(1000);  // past what was expected, not done yet
  EXPECT_LT(w.fraction(), 1.0);
  EXPECT_GT(w.fraction(), 0.99);
}

}  // namespace
}  // namespace vp

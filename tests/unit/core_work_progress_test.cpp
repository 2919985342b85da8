// The work a step is expected to take and how far it has got (work_progress.h).
#include <gtest/gtest.h>

#include "core/work_progress.h"

namespace vp {
namespace {

void runPiece(WorkProgress& w, int64_t total) {
  w.begin();
  w.add(total / 2);
  w.add(total - total / 2);
  w.finish(1);
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

namespace vp {
namespace {

// A head of 100, then `parts` parts of `perPart` each.
void runParts(WorkProgress& w, int parts, int64_t perPart) {
  w.begin();
  w.add(100);
  w.expectParts(parts);
  for (int p = 0; p < parts; ++p) w.add(perPart);
  w.finish(parts);
}

TEST(WorkProgress, ExpectsPerPartOnceTheHeadKnowsHowManyPartsFollow) {
  WorkProgress w;
  runParts(w, 1, 1000);
  EXPECT_EQ(w.expected(), 1100);
  EXPECT_EQ(w.expectedPerPart(), 1000);
  w.begin();
  w.add(100);
  EXPECT_EQ(w.expected(), 1100);  // until the parts are known: like the last piece
  w.expectParts(4);
  EXPECT_EQ(w.expected(), 100 + 4 * 1000);
  for (int p = 0; p < 4; ++p) w.add(500);  // lighter parts: forgotten a quarter at a time
  w.finish(4);
  EXPECT_EQ(w.last(), 2100);
  EXPECT_EQ(w.expectedPerPart(), 500 + 500 * 3 / 4);
  EXPECT_EQ(w.expected(), 100 + 4 * (500 + 500 * 3 / 4));
  runParts(w, 2, 3000);  // heavier ones: at once
  EXPECT_EQ(w.expectedPerPart(), 3000);
  EXPECT_TRUE(w.valid());
}

}  // namespace
}  // namespace vp

#include <gtest/gtest.h>

#include "core/budget_clock.h"

namespace vp {
namespace {

struct FakeClock {
  double now = 100.0;
  static double read(void* self) { return static_cast<FakeClock*>(self)->now; }
  Clock clock() { return Clock{&FakeClock::read, this}; }
};

TEST(Deadline, ExpiresExactlyAtTheBudget) {
  FakeClock fake;
  Deadline d(fake.clock(), 16.0);
  EXPECT_FALSE(d.expired());
  EXPECT_NEAR(d.remainingMs(), 16.0, 1e-9);  // seconds->ms round-off
  fake.now += 0.010;
  EXPECT_FALSE(d.expired());
  EXPECT_NEAR(d.elapsedMs(), 10.0, 1e-9);
  fake.now += 0.006;
  EXPECT_TRUE(d.expired());
  EXPECT_DOUBLE_EQ(d.remainingMs(), 0.0);
}

TEST(Deadline, ZeroBudgetIsUnlimited) {
  FakeClock fake;
  Deadline d(fake.clock(), 0.0);
  fake.now += 1e6;
  EXPECT_TRUE(d.unlimited());
  EXPECT_FALSE(d.expired());
}

TEST(Deadline, ShareSplitsWhatRemains) {
  FakeClock fake;
  Deadline d(fake.clock(), 20.0);
  fake.now += 0.004;  // 16 ms remain
  Deadline half = d.share(0.5);
  EXPECT_NEAR(half.remainingMs(), 8.0, 1e-9);
  fake.now += 0.008;
  EXPECT_TRUE(half.expired());
  EXPECT_FALSE(d.expired());
}

TEST(Deadline, ShareLeavingGivesMoreWhenWhatComesLaterIsCheap) {
  FakeClock fake;
  Deadline d(fake.clock(), 20.0);
  fake.now += 0.004;  // 16 ms remain, 6 held back: 10 available
  EXPECT_NEAR(d.shareLeaving(0.5, 6.0, 2.0).remainingMs(), 8.0, 1e-9);  // all but the 2 ms later
  EXPECT_NEAR(d.shareLeaving(0.5, 6.0, 7.0).remainingMs(), 5.0, 1e-9);  // never below the equal share
  EXPECT_NEAR(d.shareLeaving(0.5, 30.0, 0.0).remainingMs(), 0.0, 1e-12);  // a reserve beyond the budget leaves nothing
  EXPECT_TRUE(Deadline(fake.clock(), 0.0).shareLeaving(0.5, 6.0, 2.0).unlimited());
}

TEST(Deadline, SteadyClockByDefault) {
  Deadline d(Clock{}, 1e4);
  EXPECT_FALSE(d.expired());
  EXPECT_GE(d.elapsedMs(), 0.0);
}

}  // namespace
}  // namespace vp

// An optimisation alive without progress is noticed after
// max(30 s, 5 x the longest generation so far), on a fake clock.
#include "studio/live/stall_watch.h"

#include <gtest/gtest.h>

namespace mrsim::studio {
namespace {

const WallTime kT0 = WallTime() + std::chrono::hours(1);

WallTime At(double s) { return AfterSeconds(kT0, s); }

TEST(StudioStallWatch, BeforeTheFirstGenerationThirtySecondsAreNormal) {
  StallWatch watch;
  EXPECT_FALSE(watch.Stalled(At(1000)));  // not started: nothing to watch
  watch.Start(0, At(0));
  watch.Update(0, At(29));
  EXPECT_FALSE(watch.Stalled(At(29)));
  EXPECT_FALSE(watch.Stalled(At(30)));
  ASSERT_TRUE(watch.Stalled(At(42)));
  EXPECT_DOUBLE_EQ(*watch.Stalled(At(42)), 42);
}

TEST(StudioStallWatch, BoundIsFiveTimesTheLongestGenerationSoFar) {
  StallWatch watch;
  watch.Start(0, At(0));
  watch.Update(1, At(12));  // 12 s
  watch.Update(2, At(16));  // 4 s
  EXPECT_DOUBLE_EQ(watch.longest(), 12);
  EXPECT_DOUBLE_EQ(watch.Bound(), 60);
  EXPECT_FALSE(watch.Stalled(At(16 + 59)));
  ASSERT_TRUE(watch.Stalled(At(16 + 61)));
  EXPECT_DOUBLE_EQ(*watch.Stalled(At(16 + 61)), 61);
}

TEST(StudioStallWatch, ShortGenerationsKeepTheThirtySecondFloor) {
  StallWatch watch;
  watch.Start(0, At(0));
  for (int g = 1; g <= 5; ++g) watch.Update(g, At(g));  // 1 s each
  EXPECT_DOUBLE_EQ(watch.Bound(), 30);
  EXPECT_FALSE(watch.Stalled(At(5 + 30)));
  EXPECT_TRUE(watch.Stalled(At(5 + 31)));
}

TEST(StudioStallWatch, ProgressEndsTheStall) {
  StallWatch watch;
  watch.Start(0, At(0));
  EXPECT_TRUE(watch.Stalled(At(40)));
  watch.Update(1, At(40));
  EXPECT_FALSE(watch.Stalled(At(41)));
  // The same count again is no progress: silent since 40 s, bound
  // 5 x 40 s = 200 s.
  watch.Update(1, At(100));
  EXPECT_FALSE(watch.Stalled(At(40 + 199)));
  EXPECT_TRUE(watch.Stalled(At(40 + 201)));
}

TEST(StudioStallWatch, GenerationsSeenTogetherShareTheirTime) {
  // Ten generations read back from a checkpoint in one poll after 20 s.
  StallWatch watch;
  watch.Start(0, At(0));
  watch.Update(10, At(20));
  EXPECT_DOUBLE_EQ(watch.longest(), 2);
  EXPECT_DOUBLE_EQ(watch.Bound(), 30);
}

TEST(StudioStallWatch, StartForgetsTheLastRun) {
  StallWatch watch;
  watch.Start(0, At(0));
  watch.Update(1, At(100));
  EXPECT_DOUBLE_EQ(watch.Bound(), 500);
  watch.Start(0, At(200));
  EXPECT_DOUBLE_EQ(watch.Bound(), 30);
  EXPECT_TRUE(watch.Stalled(At(231)));
}

}  // namespace
}  // namespace mrsim::studio

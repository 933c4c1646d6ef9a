// How the benchmarks tell a shared machine's two speed states apart, on
// fake timings.
#include "bench/common/speed_states.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "bench/common/paired_ratio.h"

namespace mrsim {
namespace {

using ::testing::ElementsAre;

// Speeds scattered by a few percent around `centre`, deterministic.
std::vector<double> Around(double centre, int n, int phase = 0) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) {
    v.push_back(centre * (1 + 0.04 * std::sin(1.7 * (i + phase))));
  }
  return v;
}

// The in-process loop at about 58 or 91 sim s per s, as these VMs gave
// it: every repeat goes to its state, the split lies between them.
TEST(SpeedStatesTest, TellsTwoSeparateClustersApart) {
  std::vector<double> speeds = Around(58, 30);
  const std::vector<double> fast = Around(91, 70, 3);
  speeds.insert(speeds.end(), fast.begin(), fast.end());
  const SpeedStates s = FindSpeedStates(speeds);
  ASSERT_TRUE(s.two_states);
  EXPECT_GT(s.threshold, 58 * 1.04);
  EXPECT_LT(s.threshold, 91 * 0.96);
  EXPECT_NEAR(s.slow_median, 58, 2);
  EXPECT_NEAR(s.fast_median, 91, 3);
  EXPECT_GT(s.separability, 0.9);
  EXPECT_EQ(s.fast_count(), 70);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(s.fast[i], i >= 30) << i;
}

// One state scattered widely is not two, symmetric or skewed: every
// repeat counts.
TEST(SpeedStatesTest, OneHumpKeepsEveryRepeat) {
  std::mt19937 random(7);
  std::normal_distribution<double> normal(80, 10);
  std::gamma_distribution<double> skewed(2, 10);
  std::vector<double> a, b;
  for (int i = 0; i < 600; ++i) {
    a.push_back(normal(random));
    b.push_back(20 + skewed(random));
  }
  for (const auto& speeds : {a, b}) {
    const SpeedStates s = FindSpeedStates(speeds);
    EXPECT_FALSE(s.two_states) << s.separability;
    EXPECT_EQ(s.fast_count(), 600);
  }
}

// Three slow outliers among a hundred are not a state of their own.
TEST(SpeedStatesTest, AFewOutliersAreNotAState) {
  std::vector<double> speeds = Around(90, 97);
  speeds.insert(speeds.end(), {20, 25, 30});
  const SpeedStates s = FindSpeedStates(speeds);
  EXPECT_FALSE(s.two_states);
  EXPECT_EQ(s.fast_count(), 100);
}

// The point of it: a loop that slows less than its baseline in the slow
// state gives pair ratios in two groups, whose median follows the share
// of fast repeats; within the fast state the ratio holds whatever the
// share.
TEST(SpeedStatesTest, RatioInTheFastStateDoesNotFollowTheShare) {
  auto run = [](int fast_rounds) {
    std::vector<double> a, b;
    for (int i = 0; i < 200; ++i) {
      const bool fast = i % 200 < fast_rounds;
      const double jitter = 1 + 0.03 * std::sin(2.3 * i);
      b.push_back((fast ? 91 : 58) * jitter);
      a.push_back((fast ? 60 : 50) * jitter);
    }
    const SpeedStates s = FindSpeedStates(b);
    return std::make_pair(
        SummarizePairs(a, b).median,
        SummarizePairs(Select(a, s.fast), Select(b, s.fast)).median);
  };
  const auto [all_few, fast_few] = run(60);
  const auto [all_many, fast_many] = run(180);
  EXPECT_GT(all_few / all_many, 1.2);
  EXPECT_NEAR(fast_few / fast_many, 1.0, 0.01);
  EXPECT_NEAR(fast_many, 60.0 / 91.0, 0.01);
}

TEST(SpeedStatesTest, TooFewRepeatsAreOneState) {
  EXPECT_FALSE(FindSpeedStates({1, 100}).two_states);
  EXPECT_EQ(FindSpeedStates({}).fast_count(), 0);
}

TEST(SpeedStatesTest, SelectKeepsTheMarkedValuesInOrder) {
  EXPECT_THAT(Select({1, 2, 3, 4}, {true, false, false, true}),
              ElementsAre(1, 4));
  EXPECT_THROW(Select({1, 2}, {true}), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim

// The statistics the benchmarks print their ratios with, on fake timings.
#include "bench/common/paired_ratio.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace mrsim {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(PairedRatioTest, MedianOfOddAndEvenCounts) {
  EXPECT_DOUBLE_EQ(Median({3, 1, 2}), 2);
  EXPECT_DOUBLE_EQ(Median({4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(Median({}), 0);
}

TEST(PairedRatioTest, RelativeIqrInterpolatesTheQuartiles) {
  // Quartiles of 1..5 are 2 and 4, the median 3.
  EXPECT_DOUBLE_EQ(RelativeIqr({5, 1, 4, 2, 3}), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(RelativeIqr({7, 7, 7, 7}), 0);
  EXPECT_DOUBLE_EQ(RelativeIqr({1}), 0);
}

// The ends of the interval are the 40th and 61st of 100 values (n/2 -+
// 0.98 sqrt(n), widened to whole ranks); with 10 or fewer values, the
// extremes.
TEST(PairedRatioTest, MedianIntervalFromOrderStatistics) {
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);
  EXPECT_DOUBLE_EQ(RelativeMedianInterval(v), (61.0 - 40.0) / 50.5);
  EXPECT_DOUBLE_EQ(RelativeMedianInterval({1, 2, 3, 4, 10}), 9.0 / 3.0);
  EXPECT_DOUBLE_EQ(RelativeMedianInterval({2}), 0);
}

// Single pairs that scatter by +-20 % still give a steady median when
// there are enough of them: the spread narrows as 1 / sqrt(n), the IQR
// does not.
TEST(PairedRatioTest, MorePairsNarrowTheSpreadNotTheIqr) {
  auto scattered = [](int n) {
    std::vector<double> a;
    for (int i = 0; i < n; ++i) a.push_back(1.0 + 0.2 * std::sin(i * 2.4));
    return SummarizePairs(a, std::vector<double>(n, 1.0));
  };
  const PairedRatio few = scattered(12), many = scattered(200);
  EXPECT_GT(few.spread, 0.2);
  EXPECT_LT(many.spread, few.spread / 3);
  EXPECT_GT(many.iqr, 0.2);
  EXPECT_NEAR(many.median, 1.0, 0.02);
}

// A load that doubles every time halfway through moves both sides of a
// pair alike: each pair still says 1.2, where the sides' own values swing
// by a factor of two.
TEST(PairedRatioTest, PairsCancelLoadThatHitsBothSides) {
  std::vector<double> a, b;
  for (int i = 0; i < 10; ++i) {
    const double load = i % 3 == 0 ? 2.0 : 1.0;
    a.push_back(1.2 * load);
    b.push_back(1.0 * load);
  }
  const PairedRatio r = SummarizePairs(a, b);
  EXPECT_NEAR(r.median, 1.2, 1e-12);
  EXPECT_NEAR(r.spread, 0, 1e-12);
  EXPECT_NEAR(r.iqr, 0, 1e-12);
  EXPECT_NEAR(r.min, 1.2, 1e-12);
  EXPECT_NEAR(r.max, 1.2, 1e-12);
  EXPECT_EQ(r.ratios.size(), 10u);
}

// One pair a burst hit cannot move the median; it shows in the extremes.
TEST(PairedRatioTest, OneOutlierMovesNeitherMedianNorSpread) {
  std::vector<double> a = {1.00, 1.01, 0.99, 1.00, 3.00, 1.00, 1.01};
  std::vector<double> b(a.size(), 1.0);
  const PairedRatio r = SummarizePairs(a, b);
  EXPECT_DOUBLE_EQ(r.median, 1.00);
  EXPECT_LT(r.iqr, 0.02);
  EXPECT_DOUBLE_EQ(r.max, 3.0);
  EXPECT_DOUBLE_EQ(r.min, 0.99);
}

TEST(PairedRatioTest, PairsWithoutABaselineAreLeftOut) {
  const PairedRatio r = SummarizePairs({2, 4, 6}, {1, 0, 3});
  EXPECT_THAT(r.ratios, ElementsAre(2.0, 2.0));
  EXPECT_DOUBLE_EQ(r.median, 2.0);
  EXPECT_THROW(SummarizePairs({1, 2}, {1}), std::invalid_argument);
}

// A B, then B A: a load rising through the run slows whichever goes
// second, and alternating puts each side second half the time.
TEST(PairedRatioTest, RunInterleavedAlternatesTheOrder) {
  std::string order;
  auto measure = [&](char name) {
    return [&order, name] {
      order += name;
      return 1.0;
    };
  };
  const auto values =
      RunInterleaved({measure('A'), measure('B'), measure('C')}, 4);
  EXPECT_EQ(order, "ABCCBAABCCBA");
  ASSERT_EQ(values.size(), 3u);
  EXPECT_EQ(values[0].size(), 4u);
}

// The load rises by 10 % with every measurement: B always second would
// read slower every pair (ratio 1.1); alternating, the median is 1.
TEST(PairedRatioTest, RunPairedCancelsDrift) {
  double load = 1.0;
  auto timed = [&load] {
    load *= 1.1;
    return load;
  };
  const PairedRatio r = RunPaired(timed, timed, 10);
  EXPECT_NEAR(r.median, 1.0, 0.06);
  EXPECT_EQ(r.ratios.size(), 10u);
}

TEST(PairedRatioTest, FormatPrintsValueThenSpread) {
  const PairedRatio r = SummarizePairs({1.1, 1.2, 1.3}, {1, 1, 1});
  const std::string out = FormatBench("decode_ratio", r, "x", "safe / plain");
  EXPECT_THAT(out, HasSubstr("# decode_ratio: 3 pairs, ratios 1.100-1.300 (IQR "
                             "8.3%); median safe / plain 1.2 / 1\n"));
  EXPECT_THAT(out, HasSubstr("BENCH decode_ratio 1.200 x\n"
                             "BENCH decode_ratio_spread 16.7 %\n"));
  EXPECT_THAT(out, HasSubstr("# decode_ratio: spread 16.7% > 5%: not a "
                             "reliable figure on this machine right now\n"));
}

TEST(PairedRatioTest, SteadyFigureHasNoWarning) {
  const PairedRatio r = SummarizePairs({1.00, 1.01, 0.99, 1.00}, {1, 1, 1, 1});
  const std::string out = FormatBench("viewer_fps_ratio", r, "x");
  EXPECT_THAT(out, HasSubstr("BENCH viewer_fps_ratio 1.000 x\n"));
  EXPECT_THAT(out, Not(HasSubstr("not a reliable figure")));
}

// An efficiency above 1 is noise: printed as 1, the median kept in the
// comment.
TEST(PairedRatioTest, AtMostClampsAndSaysSo) {
  const PairedRatio r = SummarizePairs({1.02, 1.03, 1.04}, {1, 1, 1});
  const std::string out = FormatBenchAtMost("farm_efficiency", r, 1.0, "x");
  EXPECT_THAT(out, HasSubstr("BENCH farm_efficiency 1.000 x\n"));
  EXPECT_THAT(out, HasSubstr("median 1.030 clamped to 1.000"));
  const PairedRatio low = SummarizePairs({0.8, 0.9}, {1, 1});
  EXPECT_THAT(FormatBenchAtMost("farm_efficiency", low, 1.0, "x"),
              HasSubstr("BENCH farm_efficiency 0.850 x\n"));
}

TEST(PairedRatioTest, FewerThanTwoPairsIsNotReliable) {
  EXPECT_THAT(FormatBench("x_ratio", SummarizePairs({1}, {0}), "x"),
              HasSubstr("# x_ratio: 0 pairs: not a reliable figure"));
  EXPECT_THAT(FormatBench("x_ratio", SummarizePairs({1}, {1}), "x"),
              HasSubstr("# x_ratio: 1 pairs: not a reliable figure"));
}

}  // namespace
}  // namespace mrsim

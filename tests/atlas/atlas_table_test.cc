// The gait atlas's table, tolerances and comparison, without physics.
#include "gait_controller/atlas_table.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "gait_controller/atlas_deviation.h"
#include "gait_controller/gait_atlas.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

AtlasLine SampleLine() {
  AtlasLine l;
  l.name = "forward";
  l.robot = "pitch x11";
  l.samples = 1;
  l.at(AtlasQuantity::kSpeed) = {0.0227, 0, 0.00075};
  l.at(AtlasQuantity::kDrift) = {0.00001, 0, 0.0003};
  l.at(AtlasQuantity::kRise) = {0, 0, 0.0003};
  l.at(AtlasQuantity::kHeading) = {0.01, 0, 0.3};
  l.at(AtlasQuantity::kRoll) = {-0.5, 0.01, 1.0};
  return l;
}

// Five runs with the given speeds and headings, nothing else moving.
std::vector<GaitOutcome> Runs(const std::vector<double>& speeds,
                              const std::vector<double>& headings) {
  std::vector<GaitOutcome> runs;
  for (size_t i = 0; i < speeds.size(); ++i) {
    GaitOutcome o;
    o.speed = speeds[i];
    o.heading_deg = headings[i];
    runs.push_back(o);
  }
  return runs;
}

TEST(AtlasTable, WrittenTableReadsBackTheSameLines) {
  AtlasLine chaotic = SampleLine();
  chaotic.name = "serpenoid";
  chaotic.robot = "pitch-yaw x11 wheels";
  chaotic.samples = 5;
  const std::string text = FormatAtlasTable({SampleLine(), chaotic});
  EXPECT_THAT(text, HasSubstr("gait_atlas --write docs/gait_atlas.csv"));
  EXPECT_THAT(text, HasSubstr(",rise_bl_s,rise_spread,rise_tolerance,"));
  EXPECT_THAT(text, HasSubstr(",roll_deg,roll_spread,roll_tolerance\n"));
  const std::vector<AtlasLine> back = ParseAtlasTable(text, "t.csv");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].name, "serpenoid");
  EXPECT_EQ(back[1].robot, "pitch-yaw x11 wheels");
  EXPECT_EQ(back[1].samples, 5);
  for (int q = 0; q < kAtlasQuantities; ++q) {
    EXPECT_DOUBLE_EQ(back[0].values[q].value, SampleLine().values[q].value);
    EXPECT_DOUBLE_EQ(back[0].values[q].tolerance,
                     SampleLine().values[q].tolerance);
  }
}

TEST(AtlasTable, ABadNumberIsNamedWithItsLineAndField) {
  std::string text = FormatAtlasTable({SampleLine()});
  text.replace(text.find("0.0227"), 6, "fast");
  try {
    ParseAtlasTable(text, "t.csv");
    FAIL() << "parsed a bad number";
  } catch (const AtlasTableError& e) {
    EXPECT_THAT(e.what(), HasSubstr("t.csv:6: speed"));
    EXPECT_THAT(e.what(), HasSubstr("'fast'"));
  }
}

TEST(AtlasTable, AMissingLineIsAnError) {
  EXPECT_THROW(FindAtlasLine({SampleLine()}, "rolling"), AtlasTableError);
}

TEST(AtlasCheck, OnlyAQuantityBeyondItsToleranceIsReported) {
  const AtlasLine l = SampleLine();
  // Speed 0.0007 off (tolerance 0.00075), heading 0.31 deg off (0.3).
  const auto d = CompareAtlasLine(l, {0.0234, 0.00001, 0, 0.32, -0.5});
  ASSERT_EQ(d.size(), 5u);
  EXPECT_FALSE(d[0].beyond);
  EXPECT_TRUE(d[3].beyond);
  EXPECT_TRUE(AnyBeyond(d));
  const std::string message = DescribeAtlasDeviations(d);
  EXPECT_THAT(message, HasSubstr("gait atlas line 'forward' moved: heading "
                                 "0.01 -> 0.32 deg (+0.31"));
  EXPECT_THAT(message, Not(HasSubstr("speed")));
  EXPECT_THAT(message, HasSubstr("gait_atlas --write docs/gait_atlas.csv"));
  EXPECT_THAT(message, HasSubstr("docs/physics.md"));
}

TEST(AtlasCheck, AnUnchangedLinePassesAndARunThatFailedDoesNot) {
  const AtlasLine l = SampleLine();
  EXPECT_FALSE(
      AnyBeyond(CompareAtlasLine(l, {0.0227, 0.00001, 0, 0.01, -0.5})));
  EXPECT_EQ(DescribeAtlasDeviations(
                CompareAtlasLine(l, {0.0227, 0.00001, 0, 0.01, -0.5})),
            "");
  EXPECT_TRUE(AnyBeyond(CompareAtlasLine(l, {NAN, 0.00001, 0, 0.01, -0.5})));
}

TEST(AtlasTolerance, ARegularLineKeepsItsNominalRunAndTheFloor) {
  AtlasEntry e;
  e.name = "regular";
  // Speeds that differ in the 7th digit: the floor (2 % + 0.0003) rules.
  std::vector<double> speeds;
  for (size_t i = 0; i < kAtlasSpreadFactors.size(); ++i) {
    speeds.push_back(0.02 + 1e-7 * (kAtlasSpreadFactors[i] - 1.0) / 0.002);
  }
  const AtlasLine l =
      MakeAtlasLine(e, Runs(speeds, std::vector<double>(speeds.size(), 1.0)));
  EXPECT_EQ(l.samples, 1);
  EXPECT_DOUBLE_EQ(l.at(AtlasQuantity::kSpeed).value, 0.02);
  EXPECT_NEAR(l.at(AtlasQuantity::kSpeed).tolerance, 0.02 * 0.02 + 0.0003,
              1e-12);
  EXPECT_NEAR(l.at(AtlasQuantity::kHeading).tolerance, 0.02 + 0.3, 1e-12);
}

TEST(AtlasTolerance, AChaoticLineIsCheckedByItsMeanWithinFourSpreads) {
  AtlasEntry e;
  e.name = "chaotic";
  // Speeds jumping by +-0.001 from run to run; the five runs the check
  // repeats (factors 0.998, 0.999, 1, 1.001, 1.002) are the 1st, 4th, 7th,
  // 10th and 13th.
  std::vector<double> speeds;
  for (size_t i = 0; i < kAtlasSpreadFactors.size(); ++i) {
    speeds.push_back(0.013 + (i % 2 == 0 ? -0.001 : 0.001));
  }
  const AtlasLine l =
      MakeAtlasLine(e, Runs(speeds, std::vector<double>(speeds.size(), 0.0)));
  EXPECT_EQ(l.samples, 5);
  const AtlasValue& v = l.at(AtlasQuantity::kSpeed);
  EXPECT_NEAR(v.value, 0.013 + (-1 + 1 - 1 + 1 - 1) * 0.001 / 5, 1e-12);
  double mean = 0;
  for (double x : speeds) mean += x / speeds.size();
  double squares = 0;
  for (double x : speeds) squares += (x - mean) * (x - mean);
  const double sd = std::sqrt(squares / (speeds.size() - 1));
  EXPECT_NEAR(v.spread, sd, 1e-12);
  EXPECT_NEAR(v.tolerance, 4 * sd * std::sqrt(2.0 / 5), 1e-12);
}

TEST(AtlasTolerance, ALineNeedsARunAtEverySpreadFactor) {
  AtlasEntry e;
  e.name = "short";
  EXPECT_THROW(
      MakeAtlasLine(e, Runs({0.01, 0.01, 0.01, 0.01, 0.01}, {0, 0, 0, 0, 0})),
      std::invalid_argument);
}

}  // namespace
}  // namespace mrsim

// The optimisation setup saved in a scenario file (<optimization>): every
// field survives a write and a read, files without it still load, and a bad
// value names the file, line and field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/reality_gap_limits.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

Scenario Chain() {
  ChainScenarioOptions options;
  options.chain.modules = 2;
  return MakeChainScenario(options);
}

// The file with `xml` (an <optimization> element) after <settings>.
std::string WithSetup(const std::string& setup_xml) {
  std::string xml = WriteScenarioString(Chain());
  const size_t at = xml.find("</settings>");
  EXPECT_NE(at, std::string::npos);
  xml.insert(at + std::string("</settings>").size(), "\n  " + setup_xml);
  return xml;
}

TEST(OptimizationSettingsXml, RoundTripKeepsEveryField) {
  Scenario s = Chain();
  OptimizationSettings o;
  o.algorithm = "cmaes";
  o.generations = 7;
  o.population = 9;
  o.seed = 42;
  o.episode = 3.5;
  o.controller = "cpg";
  // A genome file's text, with characters XML escapes.
  o.genome =
      "<genome robot=\"robot0\">\n  <gene name=\"T\" lower=\"1\" upper=\"6\" "
      "start=\"3\"/>\n</genome>\n";
  o.task = "slope";
  o.base_gait = "turn_left";
  o.distance = "net";
  o.w_distance = 2;
  o.w_speed = 0.25;
  o.w_energy = 0.01;
  o.w_drift = 0.5;
  o.w_fall = 3;
  o.robust = 4;
  o.robust_mode = "worst";
  o.allow_overlap = true;
  o.algorithm_settings = "cmaes-sigma=0.2";
  o.gap_sensor_noise = 0.1;
  o.gap_sensor_bias = 0.2;
  o.gap_joint_noise = 0.03;
  o.gap_motor_noise = 0.5;
  o.gap_latency = 0.05;
  o.gap_backlash = 0.04;
  o.gap_max_accel = 0;
  o.gap_friction_range = 0.5;
  o.gap_mass_range = 0.25;
  o.gap_gain_range = 0;
  o.gap_terrain_range = 0.75;
  s.optimization = o;
  const std::string xml = WriteScenarioString(s);
  EXPECT_THAT(xml, HasSubstr("<optimization>"));
  const Scenario back = ReadScenarioString(xml, "opt.xml", "");
  ASSERT_TRUE(back.optimization.has_value());
  EXPECT_EQ(back.optimization->genome, o.genome);
  EXPECT_EQ(back.optimization->algorithm, "cmaes");
  EXPECT_EQ(back.optimization->seed, 42);
  EXPECT_EQ(back.optimization->episode, 3.5);
  EXPECT_TRUE(back.optimization->allow_overlap);
  EXPECT_THAT(xml, HasSubstr("<gapMotorNoise>0.5</gapMotorNoise>"));
  EXPECT_EQ(back.optimization->gap_latency, 0.05);
  EXPECT_EQ(back.optimization->gap_max_accel, 0);
  EXPECT_TRUE(*back.optimization == o);
  EXPECT_TRUE(back == s);
  EXPECT_EQ(WriteScenarioString(back), xml);
}

TEST(OptimizationSettingsXml, FileWithoutTheSetupHasNone) {
  const Scenario back =
      ReadScenarioString(WriteScenarioString(Chain()), "a", "");
  EXPECT_FALSE(back.optimization.has_value());
  EXPECT_EQ(WriteScenarioString(back).find("<optimization>"),
            std::string::npos);
}

TEST(OptimizationSettingsXml, LeftOutFieldsTakeTheDefaults) {
  const Scenario s = ReadScenarioString(
      WithSetup("<optimization><genes>cpg</genes></optimization>"), "a.xml",
      "");
  ASSERT_TRUE(s.optimization.has_value());
  OptimizationSettings expected;
  expected.genes = "cpg";
  EXPECT_TRUE(*s.optimization == expected);
  // Empty texts and a false allowOverlap are not written.
  const std::string xml = WriteScenarioString(s);
  EXPECT_EQ(xml.find("<genome"), std::string::npos);
  EXPECT_EQ(xml.find("<allowOverlap"), std::string::npos);
  // The reality gap left out is RealityGap::Typical()'s, and not written.
  EXPECT_EQ(s.optimization->gap_motor_noise, kGapTypicalMotorNoise);
  EXPECT_EQ(s.optimization->gap_friction_range, kGapTypicalFrictionRange);
  EXPECT_EQ(xml.find("<gap"), std::string::npos);
}

int SetupLine(const std::string& xml) {
  const size_t at = xml.find("<optimization>");
  int line = 1;
  for (size_t i = 0; i < at; ++i) line += xml[i] == '\n';
  return line;
}

void ExpectRefused(const std::string& setup_xml, const std::string& field,
                   const std::string& expected) {
  const std::string xml = WithSetup(setup_xml);
  try {
    ReadScenarioString(xml, "d.xml", "");
    ADD_FAILURE() << "accepted " << setup_xml;
  } catch (const ScenarioError& e) {
    const std::string where = "d.xml:" + std::to_string(SetupLine(xml)) +
                              ": Scenario/optimization/" + field;
    EXPECT_THAT(e.what(), HasSubstr(where)) << e.what();
    EXPECT_THAT(e.what(), HasSubstr(expected)) << e.what();
  }
}

TEST(OptimizationSettingsXml, BadValuesNameTheLineAndField) {
  ExpectRefused("<optimization><generations>0</generations></optimization>",
                "generations", "expected");
  ExpectRefused("<optimization><population>-2</population></optimization>",
                "population", "expected");
  ExpectRefused("<optimization><episode>0</episode></optimization>", "episode",
                "expected a positive value");
  ExpectRefused("<optimization><seed>-1</seed></optimization>", "seed",
                "expected");
  ExpectRefused("<optimization><robust>1001</robust></optimization>", "robust",
                "expected");
  ExpectRefused("<optimization><algorithm></algorithm></optimization>",
                "algorithm", "expected");
  ExpectRefused(
      "<optimization><genes>sine</genes><genome>&lt;genome/&gt;</genome>"
      "</optimization>",
      "genes", "expected genes or genome, not both");
}

TEST(OptimizationSettingsXml, RealityGapBeyondWhatThePhysicsAllowsIsRefused) {
  ExpectRefused("<optimization><gapLatency>2</gapLatency></optimization>",
                "gapLatency", "expected");
  ExpectRefused(
      "<optimization><gapMotorNoise>-0.1</gapMotorNoise></optimization>",
      "gapMotorNoise", "expected");
  // A range of 1 would let a factor reach 0 (a massless frame).
  ExpectRefused("<optimization><gapMassRange>1</gapMassRange></optimization>",
                "gapMassRange", "expected");
  const Scenario at_max = ReadScenarioString(
      WithSetup("<optimization><gapBacklash>0.5</gapBacklash>"
                "<gapFrictionRange>0.99</gapFrictionRange></optimization>"),
      "d.xml", "");
  EXPECT_EQ(at_max.optimization->gap_backlash, kGapMaxBacklash);
  EXPECT_EQ(at_max.optimization->gap_friction_range, kGapMaxRange);
}

}  // namespace
}  // namespace mrsim

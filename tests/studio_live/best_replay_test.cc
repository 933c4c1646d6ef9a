// "Watch best" and "Jump to generation" play an individual as the
// optimiser builds it: body genes applied to the design, gait genes to the
// base gait, written as files a run can start from.
#include "studio/live/best_replay.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "gait_controller/gait_file.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

using testing::SourcePath;
using testing::TempDir;

OptimiseOptions Snake(const std::string& genome) {
  OptimiseOptions o;
  o.scenario_path = SourcePath("scenarios/snake11.xml");
  o.genome = ReadGenomeFile(SourcePath("scenarios/" + genome));
  o.base_gait = "forward";
  return o;
}

TEST(StudioBestReplay, BodyGenesBuildTheBestsOwnRobot) {
  const OptimiseOptions o = Snake("snake_body.genome.xml");
  GenerationRow row;
  row.generation = 2;
  row.best = 0.31;
  row.genes = {{"A_pitch", 0.75},   {"phi_pitch", 1.5},   {"T", 3},
               {"module_count", 7}, {"module_mass", 0.2}, {"module_scale", 1},
               {"joint_kp", 12},    {"joint_max_vel", 4}, {"sensor_after", -1}};
  const BestReplay best = MakeBestReplay(o, row);
  EXPECT_TRUE(best.body);
  EXPECT_EQ(best.generation, 2);
  EXPECT_EQ(best.robot, "snake");
  ASSERT_EQ(best.scenario.robots.size(), 1u);
  EXPECT_EQ(best.scenario.robots[0].modules.size(), 7u);
  EXPECT_EQ(ReadScenarioFile(o.scenario_path).robots[0].modules.size(), 11u);
  const std::vector<double> p = best.gait.parameters.ToVector();
  EXPECT_EQ(p[0], 0.75);  // A_pitch
  EXPECT_EQ(p[2], 1.5);   // phi_pitch
  EXPECT_EQ(p[4], 3);     // T
  // Genes not in the genome keep the base gait's values.
  EXPECT_EQ(p[1], ResolveGait("forward").parameters.ToVector()[1]);
}

TEST(StudioBestReplay, GaitGenesAloneLeaveTheDesignsBody) {
  const OptimiseOptions o = Snake("forward_gait.genome.xml");
  GenerationRow row;
  for (const GeneSpec& g : o.genome.genes) row.genes[g.name] = g.lower;
  const BestReplay best = MakeBestReplay(o, row);
  EXPECT_FALSE(best.body);
  EXPECT_TRUE(best.scenario == ReadScenarioFile(o.scenario_path));
}

TEST(StudioBestReplay, WritesTheFilesTheRunStartsFrom) {
  const OptimiseOptions o = Snake("snake_body.genome.xml");
  GenerationRow row;
  row.genes = {{"module_count", 6}, {"T", 2.5}};  // the rest at start
  const BestReplay best = MakeBestReplay(o, row);
  const std::string dir = TempDir("best_replay") + "/watch";
  RunOptions form;
  form.clock = ClockMode::kFast;
  form.lcm_url = "udpm://239.255.76.67:7001?ttl=0";
  const RunOptions run = WriteBestReplay(best, dir, form);
  EXPECT_EQ(run.clock, ClockMode::kFast);
  EXPECT_EQ(run.lcm_url, form.lcm_url);
  EXPECT_EQ(run.robots, std::vector<std::string>{"snake"});
  ASSERT_TRUE(std::filesystem::path(run.scenario_path).is_absolute());
  const Scenario written = ReadScenarioFile(run.scenario_path);
  EXPECT_EQ(written.robots[0].modules.size(), 6u);
  EXPECT_TRUE(written == best.scenario);
  const Gait gait = ReadGaitFile(run.gait);
  EXPECT_EQ(gait.parameters.ToVector(), best.gait.parameters.ToVector());
  // A command line a user could type.
  const auto specs = LiveRunner::RunSpecs(run);
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(specs[1].args[0], run.scenario_path);
}

TEST(StudioBestReplay, AScenarioThatCannotBeReadIsNamed) {
  OptimiseOptions o = Snake("forward_gait.genome.xml");
  o.scenario_path = "/nonexistent/robot.xml";
  try {
    MakeBestReplay(o, GenerationRow{});
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("robot.xml"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mrsim::studio

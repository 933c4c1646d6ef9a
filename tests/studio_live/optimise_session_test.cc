// The studio's Optimise: the mrsim-opt command line, reading its progress,
// and a real 2-generation run started the way the window starts it.
#include "studio/live/optimise_session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::SourcePath;
using testing::TempDir;

bool Has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

TEST(OptimiseSession, SpecIsTheMrsimOptCommandLine) {
  OptimiseOptions o;
  o.scenario_path = "snake.xml";
  o.out_dir = "out";
  o.algorithm = "ga";
  o.generations = 3;
  o.farm = true;
  o.lcm_url = "udpm://239.255.76.67:7001?ttl=0";
  const ProcessSpec spec = OptimiseSession::Spec(o, "g.xml");
  EXPECT_EQ(spec.program, "mrsim-opt");
  EXPECT_EQ(spec.args[0], "snake.xml");
  EXPECT_TRUE(Has(spec.args, "--farm"));
  EXPECT_TRUE(Has(spec.args, o.lcm_url));
  EXPECT_TRUE(Has(spec.args, "ga"));
  EXPECT_FALSE(Has(spec.args, "--jump-to"));
  o.jump_to = 2;
  EXPECT_TRUE(Has(OptimiseSession::Spec(o, "g.xml").args, "--jump-to"));
  o.algorithm = "hillclimb";
  EXPECT_THROW(OptimiseSession::Spec(o, "g.xml"), std::invalid_argument);
  o.algorithm = "ga";
  o.population = 0;
  EXPECT_THROW(OptimiseSession::Spec(o, "g.xml"), std::invalid_argument);
}

TEST(OptimiseSession, ReadsGenerationsAndStopsAtAHalfWrittenLine) {
  const std::string csv =
      "generation,best,mean,worst,best_so_far,failed,A_pitch,T\n"
      "0,0.5,0.25,0,0.5,0,1,4\n"
      "1,0.75,0.5,0.125,0.75,1,0.9,3.5\n"
      "2,0.7,0.6";
  const auto rows = OptimiseSession::ParseGenerations(csv);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].generation, 1);
  EXPECT_EQ(rows[1].best, 0.75);
  EXPECT_EQ(rows[1].failed, 1);
  EXPECT_EQ(rows[1].genes.at("T"), 3.5);
  EXPECT_THROW(OptimiseSession::ParseGenerations(
                   "generation,best,mean,worst,best_so_far,failed\n"
                   "0,x,0,0,0,0\n"),
               std::runtime_error);
}

TEST(OptimiseSession, ATwoGenerationRunCompletesWithItsProgressAndBest) {
  const std::string dir = TempDir("optimise_session");
  OptimiseSession session(
      {std::filesystem::path(BinaryPath("bin/mrsim-opt")).parent_path()});
  OptimiseOptions o;
  o.scenario_path = SourcePath("scenarios/snake11.xml");
  o.out_dir = dir + "/run";
  o.genome = ReadGenomeFile(SourcePath("scenarios/forward_gait.genome.xml"));
  o.algorithm = "cmaes";
  o.generations = 2;
  o.population = 4;
  o.episode_s = 1;
  session.Start(o);
  const auto end = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!session.progress().finished &&
         std::chrono::steady_clock::now() < end) {
    session.Poll(100);
  }
  session.Poll();  // the last generations.csv
  std::string console;
  for (const auto& l : session.console()) console += l + "\n";
  ASSERT_TRUE(session.progress().finished) << console;
  EXPECT_EQ(session.progress().exit_code, 0) << console;
  ASSERT_EQ(session.progress().rows.size(), 2u) << console;
  EXPECT_GT(session.progress().evals_per_s, 0) << console;
  EXPECT_GE(session.progress().workers, 1);
  const auto best = session.BestGenes();
  ASSERT_TRUE(best.count("A_pitch")) << console;
  EXPECT_TRUE(std::filesystem::exists(o.out_dir + "/best_gait.xml"));
  EXPECT_TRUE(std::filesystem::exists(o.out_dir + "/studio.genome.xml"));
}

}  // namespace
}  // namespace mrsim

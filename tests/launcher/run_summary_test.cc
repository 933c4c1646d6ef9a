// The demo's last line (launcher/run_summary.h) in process.
#include "launcher/run_summary.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "sim_core/scenario/chain_builder.h"

namespace mrsim {
namespace {

TEST(RunSummary, ARobotThatDidNotMoveReadsZeroWithoutAMinus) {
  Scenario scenario;
  scenario.robots.push_back(MakeChain(ChainOptions{}));
  const Physics start(scenario);
  Physics end(scenario);
  end.Step(50);  // lying still: it settles by far less than a millimetre
  const RunSummary summary = SummarizeRun(start, end);
  ASSERT_EQ(summary.robots.size(), 1u);
  EXPECT_LT(summary.robots[0].distance(), 5e-4);
  const std::string line = FormatRunSummary(summary);
  EXPECT_EQ(line.find("-0.000"), std::string::npos) << line;
  EXPECT_NE(line.find("snake moved 0.000 m (dx +0.000, dy +0.000)"),
            std::string::npos)
      << line;
}

TEST(RunSummary, AnEndOfAnotherScenarioIsRefused) {
  Scenario one, two;
  one.robots.push_back(MakeChain(ChainOptions{}));
  two = one;
  ChainOptions other;
  other.name = "worm";
  two.robots.push_back(MakeChain(other));
  EXPECT_THROW(SummarizeRun(Physics(one), Physics(two)), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim

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

// Objects by the names the user gave them, as overlap messages name them;
// an object without one (a generated GUID) by its index in the file.
TEST(RunSummary, NamesSceneObjectsAsTheUserCalledThem) {
  Scenario scenario;
  scenario.robots.push_back(MakeChain(ChainOptions{}));
  SceneObject ball;
  ball.guid = "ball";
  ball.position = Eigen::Vector3d(1.0, 0.0, 0.05);
  SceneObject unnamed = ball;
  unnamed.guid = "7b579252-58ce-4fb0-937f-57c24696363f";
  unnamed.position = Eigen::Vector3d(2.0, 0.0, 0.05);
  scenario.scene_objects = {ball, unnamed};
  const Physics start(scenario);
  const RunSummary summary = SummarizeRun(start, start);
  ASSERT_EQ(summary.objects.size(), 2u);
  EXPECT_EQ(summary.objects[0].name, "ball");
  EXPECT_EQ(summary.objects[1].name, "object 1");
  const std::string line = FormatRunSummary(summary);
  EXPECT_NE(line.find("; ball displaced 0.000 m"), std::string::npos) << line;
  EXPECT_NE(line.find("; object 1 displaced 0.000 m"), std::string::npos)
      << line;
  EXPECT_EQ(line.find("object0"), std::string::npos) << line;
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

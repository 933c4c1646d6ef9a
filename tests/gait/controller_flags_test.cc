// The flags mrsim-gait and mrsim-lua share: how the sender, the joint axes,
// the no-axes warning and the rate check resolve for either program.
#include "gait_controller/process/controller_flags.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/parse_flags.h"

namespace mrsim {
namespace {

constexpr char kWarning[] = "warning: no axes";

struct Parsed {
  explicit Parsed(const std::string& kind) : flags(kind) {}
  ControllerFlags flags;
  std::string prefix = "MRSIM";
  double rate = 100.0;
  bool exit_with_sim = false;
};

// Parses `args` as program `kind` and resolves them with kWarning.
void ParseAndFinish(Parsed* p, std::vector<std::string> args) {
  CLI::App app;
  p->flags.AddFlags(app, {&p->prefix, &p->rate, &p->exit_with_sim},
                    {"the joint axes", "rate", "exit"});
  testing::ParseFlags(app, "mrsim-" + p->flags.kind, args);
  p->flags.Finish(kWarning);
}

std::string UsageMessage(Parsed* p, const std::vector<std::string>& args) {
  try {
    ParseAndFinish(p, args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(ControllerFlags, ScenarioAndAxesTogetherAreRefusedNamingBoth) {
  Parsed p("gait");
  EXPECT_EQ(UsageMessage(&p, {"--robot", "snake", "--scenario", "s.xml",
                              "--axes", "pitch"}),
            "give --scenario or --axes, not both");
}

TEST(ControllerFlags, SenderDefaultsToKindAndRobot) {
  Parsed gait("gait");
  ParseAndFinish(&gait, {"--robot", "snake"});
  EXPECT_EQ(gait.flags.sender, "gait-snake");
  Parsed lua("lua");
  ParseAndFinish(&lua, {"--robot", "snake"});
  EXPECT_EQ(lua.flags.sender, "lua-snake");
}

TEST(ControllerFlags, NameGivesTheSender) {
  Parsed p("lua");
  ParseAndFinish(&p, {"--robot", "snake", "--name", "mine"});
  EXPECT_EQ(p.flags.sender, "mine");
}

TEST(ControllerFlags, WithoutScenarioOrAxesWarnsAndAssumesPitchYaw) {
  Parsed p("gait");
  ParseAndFinish(&p, {"--robot", "snake"});
  EXPECT_EQ(p.flags.warning, kWarning);
  EXPECT_EQ(p.flags.axes_for(3),
            (std::vector<Axis>{Axis::kPitch, Axis::kYaw, Axis::kPitch}));
}

TEST(ControllerFlags, AxesGiveTheAxesWithoutAWarning) {
  Parsed p("gait");
  ParseAndFinish(&p, {"--robot", "snake", "--axes", "yaw"});
  EXPECT_TRUE(p.flags.warning.empty());
  EXPECT_EQ(p.flags.axes_for(2), (std::vector<Axis>{Axis::kYaw, Axis::kYaw}));
}

TEST(ControllerFlags, ScenarioGivesTheAxesWithoutAWarning) {
  ChainScenarioOptions options;
  options.chain.name = "snake";
  options.chain.modules = 3;
  const std::string path = testing::TempDir("controller_flags") + "/design.xml";
  WriteScenarioFile(MakeChainScenario(options), path);
  Parsed p("lua");
  ParseAndFinish(&p, {"--robot", "snake", "--scenario", path});
  EXPECT_TRUE(p.flags.warning.empty());
  EXPECT_FALSE(p.flags.axes_for(2).empty());
}

TEST(ControllerFlags, BadAxesAreAUsageError) {
  Parsed p("gait");
  EXPECT_NE(UsageMessage(&p, {"--robot", "snake", "--axes", "sideways"}), "");
}

TEST(ControllerFlags, NegativeRateIsRefusedNamingTheFlag) {
  Parsed p("lua");
  EXPECT_EQ(UsageMessage(&p, {"--robot", "snake", "--rate", "-1"}),
            "--rate must be >= 0");
}

TEST(ControllerFlags, FlagsWriteTheNodeOptions) {
  Parsed p("gait");
  ParseAndFinish(&p, {"--robot", "snake", "--prefix", "P", "--rate", "50",
                      "--exit-with-sim"});
  EXPECT_EQ(p.prefix, "P");
  EXPECT_EQ(p.rate, 50.0);
  EXPECT_TRUE(p.exit_with_sim);
}

}  // namespace
}  // namespace mrsim

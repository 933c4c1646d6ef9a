// mrsim-scenario's work in process: each subcommand's flags and what it
// writes (scenario_tool_test.cc runs the real program).
#include "sim_core/scenario_tool/scenario_command.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/parse_flags.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

// The command the given arguments (after the program name) make.
ScenarioCommand Parse(std::vector<std::string> args) {
  CLI::App app;
  ScenarioCommand command;
  AddScenarioFlags(app, command);
  testing::ParseFlags(app, "mrsim-scenario", args);
  return command;
}

std::string ErrorOf(const ScenarioCommand& command) {
  std::ostringstream out, info;
  try {
    RunScenarioCommand(command, out, info);
  } catch (const ScenarioInputError& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioCommand, NewWritesTheChainItsFlagsDescribe) {
  const ScenarioCommand command =
      Parse({"new", "--modules", "4", "--pattern", "yaw", "--sensors=-1,2",
             "--name", "worm"});
  EXPECT_EQ(command.action, ScenarioAction::kNew);
  std::ostringstream out, info;
  RunScenarioCommand(command, out, info);
  const Scenario s = ReadScenarioString(out.str(), "out", ".");
  ASSERT_EQ(s.robots.size(), 1u);
  EXPECT_EQ(s.robots[0].name, "worm");
  EXPECT_EQ(s.robots[0].modules.size(), 4u);
  EXPECT_EQ(s.robots[0].sensor_modules.size(), 2u);
  EXPECT_EQ(info.str(), "");  // stdout only: nothing said about a file
}

TEST(ScenarioCommand, EachSubcommandSetsItsAction) {
  EXPECT_EQ(Parse({"validate", "a.xml"}).action, ScenarioAction::kValidate);
  EXPECT_EQ(Parse({"info", "a.xml"}).action, ScenarioAction::kInfo);
  EXPECT_EQ(Parse({"schema"}).action, ScenarioAction::kSchema);
  EXPECT_EQ(Parse({"export-mjcf", "a.xml"}).action, ScenarioAction::kExport);
  const ScenarioCommand convert =
      Parse({"convert", "in.xml", "out.xml", "--scale", "0.01"});
  EXPECT_EQ(convert.action, ScenarioAction::kConvert);
  EXPECT_EQ(convert.file, "in.xml");
  EXPECT_EQ(convert.out_path, "out.xml");
  EXPECT_DOUBLE_EQ(convert.scale, 0.01);
}

TEST(ScenarioCommand,
     ConvertingAnOriginalFileUnscaledSaysLengthsStayAsTheyAre) {
  const std::string original =
      testing::SourcePath("scenarios/mrsim_original.xml");
  const std::string out =
      testing::TempDir("scenario_command_convert") + "/a.xml";
  for (const char* scale : {"1", "0.01"}) {
    std::ostringstream text, info;
    RunScenarioCommand(Parse({"convert", "--from", "unity-y-up", original, out,
                              "--scale", scale}),
                       text, info);
    EXPECT_EQ(info.str().find("without --scale 0.01") != std::string::npos,
              std::string(scale) == "1")
        << info.str();
  }
}

TEST(ScenarioCommand, BadInputNamesTheFlagOrFile) {
  ScenarioCommand sensors = Parse({"new", "--sensors", "front"});
  EXPECT_THAT(ErrorOf(sensors), HasSubstr("--sensors: expected none, all, "
                                          "between or a comma list"));
  ScenarioCommand scale =
      Parse({"convert", "in.xml", "out.xml", "--scale", "0"});
  EXPECT_THAT(ErrorOf(scale), HasSubstr("--scale: expected a positive"));
  ScenarioCommand missing = Parse({"validate", "/nonexistent/s.xml"});
  EXPECT_THAT(ErrorOf(missing),
              HasSubstr("/nonexistent/s.xml: cannot open the file"));
  EXPECT_EQ(ErrorOf(Parse({"new", "--modules", "0"})),
            "--modules: modules must be at least 1, got 0");
  EXPECT_EQ(ErrorOf(Parse({"new", "--sensors", "99"})),
            "--sensors: sensor module after module 99 is outside [-1, 10]");
  EXPECT_THAT(
      ErrorOf(Parse({"new", "--sensors", "2", "--front-distance-sensor"})),
      HasSubstr("--front-distance-sensor: a front distance sensor "
                "needs a sensor module in front of module 0"));
  // A friction that is not a friction is refused, not silently left out.
  EXPECT_EQ(ErrorOf(Parse({"new", "--friction", "-1"})),
            "--friction: expected a number >= 0, got -1");
  EXPECT_THAT(ErrorOf(Parse({"new", "--friction", "nan"})),
              HasSubstr("--friction: expected a number >= 0"));
}

TEST(ScenarioCommand, NewWithFrictionZeroWritesTheFrictionPair) {
  std::ostringstream out, info;
  RunScenarioCommand(Parse({"new", "--friction", "0"}), out, info);
  const Scenario s = ReadScenarioString(out.str(), "out", ".");
  ASSERT_EQ(s.contact_frictions.size(), 1u);
  EXPECT_EQ(s.contact_frictions[0].friction, 0.0);
}

}  // namespace
}  // namespace mrsim

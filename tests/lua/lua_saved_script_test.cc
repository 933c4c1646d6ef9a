// mrsim-lua without --script runs the Lua script a design carries in its
// run settings, so `mrsim-sim FILE` and `mrsim-lua --scenario FILE` run
// what the studio ran.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <string>
#include <vector>

#include "lcmtypes/runtime/usage_error.h"
#include "lua_controller/process/lua_command_line.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/parse_flags.h"

namespace mrsim {
namespace {

std::string SaveDesign(const std::string& name,
                       const std::optional<RunSettings>& run) {
  const std::string path = testing::TempDir(name) + "/design.xml";
  ChainScenarioOptions options;
  options.chain.name = "snake";
  options.chain.modules = 2;
  Scenario scenario = MakeChainScenario(options);
  scenario.run = run;
  WriteScenarioFile(scenario, path);
  return path;
}

void Parse(LuaCommandLine* line, std::vector<std::string> args) {
  CLI::App app;
  line->AddFlags(app);
  testing::ParseFlags(app, "mrsim-lua", args);
  line->Finish();
}

TEST(LuaSavedScript, WithoutScriptTheScenariosSavedScriptRuns) {
  RunSettings run;
  run.controller = ControllerKind::kLua;
  run.lua_script = "function step(t, state) return {0.25, -0.25} end\n";
  const std::string path = SaveDesign("lua_saved", run);
  LuaCommandLine line;
  Parse(&line, {"--robot", "snake", "--scenario", path});
  ASSERT_NE(line.script, nullptr);
  EXPECT_NE(line.StartLine().find("script saved in " + path), std::string::npos)
      << line.StartLine();
}

TEST(LuaSavedScript, AScenarioWithoutAScriptAsksForOne) {
  const std::string path = SaveDesign("lua_unsaved", std::nullopt);
  LuaCommandLine line;
  try {
    Parse(&line, {"--robot", "snake", "--scenario", path});
    ADD_FAILURE() << "ran without a script";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("give --script FILE"),
              std::string::npos)
        << e.what();
  }
}

TEST(LuaSavedScript, ASavedScriptWithAnErrorNamesItsLine) {
  RunSettings run;
  run.controller = ControllerKind::kLua;
  run.lua_script = "-- fine\nfunction step(t, state)\n  return {\nend\n";
  const std::string path = SaveDesign("lua_saved_bad", run);
  LuaCommandLine line;
  try {
    Parse(&line, {"--robot", "snake", "--scenario", path});
    ADD_FAILURE() << "loaded a broken script";
  } catch (const LuaScriptError& e) {
    EXPECT_GT(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("luaScript"), std::string::npos)
        << e.what();
  }
}

// The robot's cameras from --scenario: mrsim-lua then waits for the camera
// process from the first state in lockstep (docs/lua.md); none, and it
// reads no picture.
TEST(LuaSavedScript, TheScenarioSaysHowManyCamerasTheRobotHas) {
  ChainScenarioOptions options;
  options.chain.name = "snake";
  options.chain.modules = 2;
  options.chain.sensor_after = {-1};
  Scenario scenario = MakeChainScenario(options);
  ASSERT_EQ(scenario.robots[0].sensor_modules.size(), 1u);
  const std::string dir = testing::TempDir("lua_cameras");
  const std::string plain = dir + "/plain.xml";
  WriteScenarioFile(scenario, plain);
  scenario.robots[0].sensor_modules[0].cameras.resize(2);
  scenario.robots[0].sensor_modules[0].cameras[1].sensor_position = 0;
  const std::string seeing = dir + "/cameras.xml";
  WriteScenarioFile(scenario, seeing);
  const std::string script = dir + "/ctl.lua";
  { std::ofstream(script) << "function step(t, s) return {0} end\n"; }
  LuaCommandLine with, without, unknown;
  Parse(&with, {"--robot", "snake", "--scenario", seeing, "--script", script});
  EXPECT_EQ(with.options.cameras, 2);
  Parse(&without,
        {"--robot", "snake", "--scenario", plain, "--script", script});
  EXPECT_EQ(without.options.cameras, 0);
  Parse(&unknown,
        {"--robot", "snake", "--script", script, "--camera-sender", "cam-1"});
  EXPECT_EQ(unknown.options.cameras, -1);
  EXPECT_EQ(unknown.options.camera_sender, "cam-1");
}

}  // namespace
}  // namespace mrsim

// mrsim-sim given a design alone runs it as its run settings say; a flag
// given on the command line wins over the file.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/sim_process/sim_command_line.h"
#include "tests/common/child_process.h"
#include "tests/common/parse_flags.h"

namespace mrsim {
namespace {

// A two-module snake saved with `run`; returns the file's path.
std::string SaveDesign(const std::string& name, const RunSettings& run) {
  const std::string path = testing::TempDir(name) + "/design.xml";
  ChainScenarioOptions options;
  options.chain.name = "snake";
  options.chain.modules = 2;
  Scenario scenario = MakeChainScenario(options);
  scenario.run = run;
  WriteScenarioFile(scenario, path);
  return path;
}

// Parses the flags as mrsim-sim does and loads the physics.
SimOptions Parse(std::vector<std::string> args, std::string* note = nullptr) {
  CLI::App app;
  SimCommandLine line;
  line.AddFlags(app);
  testing::ParseFlags(app, "mrsim-sim", args);
  line.Finish();
  line.LoadPhysics();
  if (note) *note = line.run_note;
  return line.options;
}

TEST(SimRunSettings, TheFilesSettingsApplyWhenNoFlagIsGiven) {
  RunSettings run;
  run.clock = ClockMode::kLockstep;
  run.rate = 250;
  run.speed = 2;
  run.controller = ControllerKind::kLua;
  run.lua_script = "function step(t, state) return {} end";
  const std::string path = SaveDesign("sim_run_file", run);
  std::string note;
  const SimOptions o = Parse({path}, &note);
  EXPECT_EQ(o.clock, ClockMode::kLockstep);
  EXPECT_EQ(o.rate, 250);
  EXPECT_EQ(o.speed, 2);
  // The name the studio (and the note's command) gives the Lua node.
  EXPECT_EQ(o.controllers, std::vector<std::string>{"lua-snake"});
  EXPECT_NE(note.find("start `mrsim-lua --robot snake --scenario " + path +
                      " --name lua-snake`"),
            std::string::npos)
      << note;
}

TEST(SimRunSettings, AFlagGivenWinsOverTheFile) {
  RunSettings run;
  run.clock = ClockMode::kLockstep;
  run.rate = 250;
  run.controller = ControllerKind::kGait;
  const std::string path = SaveDesign("sim_run_flag", run);
  const SimOptions o = Parse({path, "--clock", "fast", "--rate", "50"});
  EXPECT_EQ(o.clock, ClockMode::kFast);
  EXPECT_EQ(o.rate, 50);
  EXPECT_TRUE(o.controllers.empty());
  const SimOptions l = Parse({path, "--controllers", "mine"});
  EXPECT_EQ(l.clock, ClockMode::kLockstep);
  EXPECT_EQ(l.controllers, std::vector<std::string>{"mine"});
}

TEST(SimRunSettings, AnExternalControllerRunsInLockstepWaitingForIt) {
  RunSettings run;
  run.clock = ClockMode::kRealtime;
  run.controller = ControllerKind::kExternal;
  run.external_name = "my-ctl";
  const SimOptions o = Parse({SaveDesign("sim_run_external", run)});
  EXPECT_EQ(o.clock, ClockMode::kLockstep);
  EXPECT_EQ(o.controllers, std::vector<std::string>{"my-ctl"});
}

TEST(SimRunSettings, AFileWithoutRunSettingsRunsAsTheFlagsDefault) {
  const std::string path = testing::TempDir("sim_run_none") + "/design.xml";
  ChainScenarioOptions options;
  options.chain.modules = 2;
  WriteScenarioFile(MakeChainScenario(options), path);
  std::string note;
  const SimOptions o = Parse({path}, &note);
  const SimOptions defaults;
  EXPECT_EQ(o.clock, defaults.clock);
  EXPECT_EQ(o.rate, defaults.rate);
  EXPECT_EQ(o.speed, defaults.speed);
  EXPECT_EQ(note, "");
}

}  // namespace
}  // namespace mrsim

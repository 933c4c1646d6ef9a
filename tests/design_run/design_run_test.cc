// What `mrsim run FILE` plans: the controller saved in the design, the
// simulator with the run's flags, the logger and the viewer, and the
// refusal of a design whose parts overlap.
#include "launcher/design_run.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gait_controller/gait_file.h"
#include "gait_controller/gait_presets.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/design_run/overlapping_design.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using ::testing::Contains;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::SourcePath;
using testing::TempDir;

std::vector<std::string> Names(const DesignRun& run) {
  std::vector<std::string> names;
  for (const auto& [spec, path] : run.plan().processes) {
    names.push_back(spec.name);
  }
  return names;
}

const ProcessSpec& Spec(const DesignRun& run, const std::string& name) {
  for (const auto& [spec, path] : run.plan().processes) {
    if (spec.name == name) return spec;
  }
  throw std::out_of_range("no process " + name);
}

// The args after `flag`, as one string ("--clock lockstep").
bool HasArgs(const ProcessSpec& spec, const std::vector<std::string>& args) {
  return std::search(spec.args.begin(), spec.args.end(), args.begin(),
                     args.end()) != spec.args.end();
}

// In build/bin, where every program is linked.
std::string Argv0() { return BinaryPath("bin/mrsim-run"); }

TEST(DesignRun, RunsTheLuaScriptSavedInTheDesignWithTheRunFlags) {
  DesignRunFlags flags;
  flags.file = SourcePath("scenarios/lua_serpenoid.xml");
  flags.duration = 5;
  flags.out = TempDir("design_run_lua");
  flags.lcm_url = "udpm://239.255.76.67:7811?ttl=0";
  const DesignRun run(Argv0(), flags);
  EXPECT_THAT(Names(run), ElementsAre("log", "view", "lua-snake", "sim"));

  const std::string script = flags.out + "/lua_serpenoid.controller.lua";
  EXPECT_TRUE(HasArgs(Spec(run, "lua-snake"), {"--script", script}));
  std::ifstream in(script);
  std::stringstream text;
  text << in.rdbuf();
  const Scenario s = ReadScenarioFile(flags.file);
  EXPECT_EQ(text.str(), s.run->lua_script);

  const ProcessSpec& sim = Spec(run, "sim");
  EXPECT_TRUE(sim.required);
  EXPECT_TRUE(HasArgs(sim, {"--clock", "lockstep"}));
  EXPECT_TRUE(HasArgs(sim, {"--controllers", "lua-snake"}));
  EXPECT_TRUE(HasArgs(sim, {"--duration", "5"}));
  EXPECT_TRUE(
      HasArgs(sim, {"--checkpoint-on-exit", flags.out + "/final.checkpoint"}));
  EXPECT_THAT(sim.args, ::testing::Not(Contains("--allow-overlap")));
  for (const auto& [spec, path] : run.plan().processes) {
    EXPECT_TRUE(HasArgs(spec, {"--lcm-url", flags.lcm_url})) << spec.name;
  }
  EXPECT_TRUE(HasArgs(Spec(run, "log"), {"--out", flags.out + "/csv"}));
  EXPECT_TRUE(
      HasArgs(Spec(run, "view"), {"--out", flags.out + "/lua_serpenoid.mp4"}));
}

TEST(DesignRun, ClockAndSpeedFlagsOverTheSavedRunSettings) {
  DesignRunFlags flags;
  flags.file = SourcePath("scenarios/case_study.xml");  // no <run>: gait
  flags.out = TempDir("design_run_clock");
  flags.clock = "realtime";
  flags.speed = 2.5;
  const DesignRun run(Argv0(), flags);
  EXPECT_THAT(Names(run), ElementsAre("log", "view", "gait-case_study", "sim"));
  EXPECT_TRUE(HasArgs(Spec(run, "gait-case_study"), {"--gait", "forward"}));
  EXPECT_TRUE(HasArgs(Spec(run, "sim"), {"--clock", "realtime"}));
  EXPECT_TRUE(HasArgs(Spec(run, "sim"), {"--speed", "2.5"}));
}

// A design saved by the studio after tuning the gait in its Run panel.
std::string DesignWithTunedGait(const std::string& dir,
                                const std::string& tuned_gait) {
  Scenario s = ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  s.run.emplace();
  s.run->gait = "forward";
  s.run->tuned_gait = tuned_gait;
  const std::string file = dir + "/tuned.xml";
  WriteScenarioFile(s, file);
  return file;
}

TEST(DesignRun, StartsTheRobotsWithTheGaitTunedAndSavedInTheDesign) {
  Gait tuned = *FindGaitPreset("forward");
  tuned.name = "tuned";
  tuned.parameters.amplitude_pitch = 0.8125;
  tuned.parameters.period = 3.5;
  DesignRunFlags flags;
  flags.out = TempDir("design_run_tuned");
  flags.file = DesignWithTunedGait(flags.out, WriteGaitString(tuned));
  const DesignRun run(Argv0(), flags);
  const std::string gait_file = flags.out + "/tuned.tuned.gait.xml";
  EXPECT_TRUE(HasArgs(Spec(run, "gait-case_study"), {"--gait", gait_file}));
  const Gait back = ReadGaitFile(gait_file);
  EXPECT_EQ(back.parameters.amplitude_pitch, 0.8125);
  EXPECT_EQ(back.parameters.period, 3.5);
}

TEST(DesignRun, ABrokenTunedGaitIsRefusedNamingTheFileAndField) {
  DesignRunFlags flags;
  flags.out = TempDir("design_run_tuned_bad");
  flags.file = DesignWithTunedGait(flags.out, "<gait><A_pitch>1</A_pitch>");
  try {
    const DesignRun run(Argv0(), flags);
    FAIL() << "a broken tuned gait was accepted";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr(flags.file + ": <run><tunedGait>"));
  }
}

TEST(DesignRun, LcmDefaultUrlIsUsedWhenNoLcmUrlIsGiven) {
  const std::string url = "udpm://239.255.76.67:7813?ttl=0";
  ASSERT_EQ(setenv("LCM_DEFAULT_URL", url.c_str(), 1), 0);
  DesignRunFlags flags;
  flags.file = SourcePath("scenarios/lua_serpenoid.xml");
  flags.out = TempDir("design_run_env");
  const DesignRun run(Argv0(), flags);
  unsetenv("LCM_DEFAULT_URL");
  for (const auto& [spec, path] : run.plan().processes) {
    EXPECT_TRUE(HasArgs(spec, {"--lcm-url", url})) << spec.name;
  }
}

TEST(DesignRun, WithoutLeavesOutAProcessAndRefusesNamesItDoesNotHave) {
  DesignRunFlags flags;
  flags.file = SourcePath("scenarios/lua_serpenoid.xml");
  flags.out = TempDir("design_run_without");
  flags.without = {"view", "log"};
  EXPECT_THAT(Names(DesignRun(Argv0(), flags)),
              ElementsAre("lua-snake", "sim"));
  for (const char* bad : {"sim", "viewer"}) {
    flags.without = {bad};
    try {
      DesignRun run(Argv0(), flags);
      ADD_FAILURE() << "--without " << bad << " accepted";
    } catch (const UsageError& e) {
      EXPECT_THAT(e.what(), HasSubstr(std::string("--without ") + bad));
      EXPECT_THAT(e.what(), HasSubstr("view"));
    }
  }
}

TEST(DesignRun, AnOverlappingDesignIsRefusedNamingThePartsAndHowDeep) {
  const std::string dir = TempDir("design_run_overlap");
  DesignRunFlags flags;
  flags.file = testing::WriteOverlappingDesign(dir);
  flags.out = dir + "/out";
  try {
    DesignRun run(Argv0(), flags);
    ADD_FAILURE() << "an overlapping design was planned";
  } catch (const OverlapError& e) {
    EXPECT_THAT(e.what(),
                ::testing::ContainsRegex(
                    "robot 'case_study' module 0 (front|back) frame"));
    EXPECT_THAT(e.what(), HasSubstr("scene object 'ball' by "));
    EXPECT_THAT(e.what(), HasSubstr(" mm at the start"));
    EXPECT_THAT(e.what(), HasSubstr(flags.file + ":"));
  }
  flags.allow_overlap = true;
  const DesignRun run(Argv0(), flags);
  EXPECT_THAT(Spec(run, "sim").args, Contains("--allow-overlap"));
}

}  // namespace
}  // namespace mrsim

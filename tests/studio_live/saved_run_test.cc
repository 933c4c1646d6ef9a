// How to run a design travels with it: what the Run form saves is what
// opening the file gives back, and a file from before gives the defaults.
#include "studio/live/saved_run.h"

#include <gtest/gtest.h>

#include <string>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/design/design.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

RunOptions LuaForm() {
  RunOptions o;
  o.clock = ClockMode::kLockstep;
  o.rate = 200;
  o.speed = 0.5;
  o.controller = ControllerKind::kLua;
  o.gait = "turn_left";
  o.external_name = "my-ctl";
  return o;
}

void ExpectSameForm(const RunOptions& a, const RunOptions& b) {
  EXPECT_EQ(a.clock, b.clock);
  EXPECT_EQ(a.rate, b.rate);
  EXPECT_EQ(a.speed, b.speed);
  EXPECT_EQ(a.controller, b.controller);
  EXPECT_EQ(a.gait, b.gait);
  EXPECT_EQ(a.external_name, b.external_name);
}

TEST(SavedRun, OpeningTheSavedDesignGivesTheFormItWasSavedWith) {
  const std::string path = testing::TempDir("saved_run") + "/design.xml";
  ChainScenarioOptions chain;
  chain.chain.modules = 2;
  WriteScenarioFile(MakeChainScenario(chain), path);
  const std::string script = "function step(t, state)\n  return {}\nend\n";
  {
    Design design = Design::Open(path);
    design.SetRunSettings(SettingsFromRunOptions(LuaForm(), script));
    EXPECT_TRUE(design.dirty());
    design.Save();
  }
  const Design opened = Design::Open(path);
  ASSERT_TRUE(opened.scenario().run.has_value());
  ExpectSameForm(RunOptionsFromSettings(opened.scenario().run), LuaForm());
  EXPECT_EQ(opened.scenario().run->lua_script, script);
}

TEST(SavedRun, ADesignWithoutRunSettingsOpensWithTheDefaults) {
  ExpectSameForm(RunOptionsFromSettings(std::nullopt), RunOptions{});
}

TEST(SavedRun, TheScriptIsSavedOnlyForALuaController) {
  RunOptions o = LuaForm();
  o.controller = ControllerKind::kGait;
  EXPECT_EQ(SettingsFromRunOptions(o, "x = 1").lua_script, "");
  EXPECT_EQ(SettingsFromRunOptions(LuaForm(), "x = 1").lua_script, "x = 1");
}

TEST(SavedRun, ATunedGaitIsSavedReopenedAndOnlyForTheGaitController) {
  const std::string tuned = "<gait name=\"tuned\" kind=\"linear\"/>";
  RunOptions gait_form;
  EXPECT_EQ(SettingsFromRunOptions(gait_form, "", tuned).tuned_gait, tuned);
  EXPECT_EQ(SettingsFromRunOptions(LuaForm(), "x = 1", tuned).tuned_gait, "");

  const std::string path = testing::TempDir("saved_run_tuned") + "/d.xml";
  ChainScenarioOptions chain;
  chain.chain.modules = 2;
  WriteScenarioFile(MakeChainScenario(chain), path);
  {
    Design design = Design::Open(path);
    design.SetRunSettings(SettingsFromRunOptions(gait_form, "", tuned));
    EXPECT_TRUE(design.dirty());
    design.Save();
  }
  EXPECT_EQ(Design::Open(path).scenario().run->tuned_gait, tuned);
}

TEST(SavedRun, SettingsNoRunCouldUseAreRefused) {
  Design design;
  RunSettings run;
  run.controller = ControllerKind::kExternal;
  run.external_name = "two words";
  EXPECT_THROW(design.SetRunSettings(run), DesignError);
  EXPECT_FALSE(design.scenario().run.has_value());
}

}  // namespace
}  // namespace mrsim::studio

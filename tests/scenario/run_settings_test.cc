// Run settings saved in a scenario file (<run>): every field survives a
// write and a read, files without them still load, and a bad value names
// the file, line and field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

Scenario Chain() {
  ChainScenarioOptions options;
  options.chain.modules = 2;
  return MakeChainScenario(options);
}

// The file with `run_xml` in place of its <run> element (after <settings>).
std::string WithRun(const std::string& run_xml) {
  std::string xml = WriteScenarioString(Chain());
  const size_t at = xml.find("</settings>");
  EXPECT_NE(at, std::string::npos);
  xml.insert(at + std::string("</settings>").size(), "\n  " + run_xml);
  return xml;
}

TEST(RunSettingsXml, RoundTripKeepsEveryField) {
  Scenario s = Chain();
  RunSettings run;
  run.clock = ClockMode::kLockstep;
  run.rate = 250;
  run.speed = 0.5;
  run.controller = ControllerKind::kLua;
  run.gait = "turn_left";
  // Characters XML would escape, a CDATA end and a trailing newline.
  run.lua_script =
      "-- a < b && c > d\nfunction step(t, state)\n  local s = \"]]>\"\n"
      "  return {}\nend\n";
  run.external_name = "my-ctl";
  s.run = run;
  const std::string xml = WriteScenarioString(s);
  EXPECT_THAT(xml, HasSubstr("<![CDATA[-- a < b && c > d"));
  const Scenario back = ReadScenarioString(xml, "run.xml", "");
  ASSERT_TRUE(back.run.has_value());
  EXPECT_EQ(back.run->clock, ClockMode::kLockstep);
  EXPECT_EQ(back.run->rate, 250);
  EXPECT_EQ(back.run->speed, 0.5);
  EXPECT_EQ(back.run->controller, ControllerKind::kLua);
  EXPECT_EQ(back.run->gait, "turn_left");
  EXPECT_EQ(back.run->lua_script, run.lua_script);
  EXPECT_EQ(back.run->external_name, "my-ctl");
  EXPECT_TRUE(back == s);
  EXPECT_EQ(WriteScenarioString(back), xml);
}

TEST(RunSettingsXml, FileWithoutRunSettingsHasNone) {
  const Scenario back =
      ReadScenarioString(WriteScenarioString(Chain()), "a", "");
  EXPECT_FALSE(back.run.has_value());
  EXPECT_EQ(WriteScenarioString(back).find("<run>"), std::string::npos);
}

TEST(RunSettingsXml, LeftOutFieldsTakeTheDefaults) {
  const Scenario s =
      ReadScenarioString(WithRun("<run><rate>50</rate></run>"), "a.xml", "");
  ASSERT_TRUE(s.run.has_value());
  RunSettings expected;
  expected.rate = 50;
  EXPECT_TRUE(*s.run == expected);
}

// The line of "<run>" in WithRun's text, counted from 1.
int RunLine(const std::string& xml) {
  const size_t at = xml.find("<run>");
  int line = 1;
  for (size_t i = 0; i < at; ++i) line += xml[i] == '\n';
  return line;
}

void ExpectRefused(const std::string& run_xml, const std::string& field,
                   const std::string& expected) {
  const std::string xml = WithRun(run_xml);
  try {
    ReadScenarioString(xml, "d.xml", "");
    ADD_FAILURE() << "accepted " << run_xml;
  } catch (const ScenarioError& e) {
    const std::string where =
        "d.xml:" + std::to_string(RunLine(xml)) + ": Scenario/run/" + field;
    EXPECT_THAT(e.what(), HasSubstr(where)) << e.what();
    EXPECT_THAT(e.what(), HasSubstr(expected)) << e.what();
  }
}

TEST(RunSettingsXml, BadValuesNameTheLineAndField) {
  ExpectRefused("<run><clock>slow</clock></run>", "clock",
                "expected realtime, fast or lockstep, got 'slow'");
  ExpectRefused("<run><controller>python</controller></run>", "controller",
                "expected gait, lua or external, got 'python'");
  ExpectRefused("<run><rate>0</rate></run>", "rate",
                "expected a positive value");
  ExpectRefused("<run><speed>-1</speed></run>", "speed",
                "expected a positive value");
  ExpectRefused("<run><controller>lua</controller></run>", "luaScript",
                "expected the Lua script's source");
  ExpectRefused(
      "<run><controller>external</controller><externalName>-x</externalName>"
      "</run>",
      "externalName", "for controller external, got '-x'");
  ExpectRefused("<run><luaScript>" + std::string(kMaxLuaScriptBytes + 1, 'x') +
                    "</luaScript></run>",
                "luaScript", "expected at most 65536 bytes");
}

}  // namespace
}  // namespace mrsim

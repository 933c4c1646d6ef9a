// The Lua sandbox: what a script may do, the errors it gets (with their
// line), the limits that stop a runaway script, and the shipped templates.
#include "lua_controller/lua_script.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lua_controller/lua_templates.h"

namespace mrsim {
namespace {

LuaRobotState Joints(int n) {
  LuaRobotState s;
  s.angles.assign(n, 0.0);
  s.speeds.assign(n, 0.0);
  s.torques.assign(n, 0.0);
  return s;
}

int ErrorLine(const std::string& source) {
  try {
    LuaScript script(source, "ctl.lua");
  } catch (const LuaScriptError& e) {
    return e.line();
  }
  return -1;
}

TEST(LuaScript, StepReturnsOneTargetPerJoint) {
  LuaScript script(
      "function step(t, state)\n"
      "  local out = {}\n"
      "  for i = 1, state.n do out[i] = t * i end\n"
      "  return out\n"
      "end\n",
      "ctl.lua");
  const std::vector<double> got = script.Step(0.5, Joints(3));
  EXPECT_EQ(got, (std::vector<double>{0.5, 1.0, 1.5}));
}

TEST(LuaScript, SeesTheStateAndKeepsGlobalsBetweenSteps) {
  LuaScript script(
      "calls = 0\n"
      "function step(t, s)\n"
      "  calls = calls + 1\n"
      "  return {s.angles[2] + calls, s.com[3], s.sensors[1].force,\n"
      "          s.sensors[1].distances[1], #s.axes, s.axes[1] == 'yaw' and 1 "
      "or 0}\n"
      "end\n",
      "ctl.lua");
  LuaRobotState s = Joints(6);
  s.angles[1] = 0.25;
  s.com[2] = 0.1;
  s.axes = {"yaw", "pitch", "yaw", "pitch", "yaw", "pitch"};
  s.sensors.resize(1);
  s.sensors[0].has_force = true;
  s.sensors[0].force = 3.5;
  s.sensors[0].distances = {0.7};
  EXPECT_EQ(script.Step(0, s),
            (std::vector<double>{1.25, 0.1, 3.5, 0.7, 6, 1}));
  EXPECT_EQ(script.Step(0, s)[0], 2.25);
}

// One limit for a script wherever it comes from (a file, a design's
// <run><luaScript>, the studio's editor): kMaxLuaScriptBytes.
TEST(LuaScript, AScriptOverTheOneSizeLimitIsRefused) {
  // step, then a comment line filling the script up to the limit.
  std::string source = "function step(t, s) return {} end\n--";
  source.resize(kMaxLuaScriptBytes - 1, '-');
  source.push_back('\n');
  ASSERT_EQ(source.size(), kMaxLuaScriptBytes);
  EXPECT_NO_THROW(LuaScript(source, "max.lua"));
  source.push_back('\n');
  try {
    LuaScript script(source, "over.lua");
    FAIL() << "a script of " << source.size() << " bytes was taken";
  } catch (const LuaScriptError& e) {
    EXPECT_EQ(std::string(e.what()),
              "over.lua: the script has 65537 bytes; at most 65536");
  }
}

TEST(LuaScript, SyntaxErrorNamesItsLine) {
  const std::string source =
      "function step(t, state)\n"
      "  local x = 1\n"
      "  return {x +}\n"
      "end\n";
  try {
    LuaScript script(source, "ctl.lua");
    FAIL() << "no error";
  } catch (const LuaScriptError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("ctl.lua:3:"), std::string::npos)
        << e.what();
  }
  const auto checked = LuaScript::Check(source, "ctl.lua");
  ASSERT_TRUE(checked.has_value());
  EXPECT_EQ(checked->line(), 3);
  EXPECT_FALSE(LuaScript::Check("function step() return {} end", "x"));
}

TEST(LuaScript, RuntimeErrorInStepNamesItsLine) {
  LuaScript script(
      "function step(t, state)\n"
      "  local a = nil\n"
      "  return {a.b}\n"
      "end\n",
      "ctl.lua");
  try {
    script.Step(0, Joints(1));
    FAIL() << "no error";
  } catch (const LuaScriptError& e) {
    EXPECT_EQ(e.line(), 3) << e.what();
  }
}

TEST(LuaScript, AScriptWithoutStepIsRefused) {
  EXPECT_EQ(ErrorLine("x = 1\n"), 0);
  EXPECT_EQ(ErrorLine("x = 1\nerror('no')\n"), 2);
}

TEST(LuaScript, EndlessLoopIsStoppedWithItsLine) {
  LuaLimits limits;
  limits.instructions = 1'000'000;
  LuaScript script(
      "function step(t, state)\n"
      "  while true do\n"
      "  end\n"
      "end\n",
      "ctl.lua", limits);
  try {
    script.Step(0, Joints(1));
    FAIL() << "no error";
  } catch (const LuaScriptError& e) {
    EXPECT_NE(std::string(e.what()).find("instructions"), std::string::npos);
    EXPECT_GE(e.line(), 2);
    EXPECT_LE(e.line(), 3);
  }
  // The top level is limited too.
  EXPECT_THROW(LuaScript("while true do end", "top.lua", limits),
               LuaScriptError);
}

TEST(LuaScript, PcallCannotSwallowTheInstructionLimit) {
  LuaLimits limits;
  limits.instructions = 100'000;
  LuaScript script(
      "function step(t, state)\n"
      "  while true do pcall(function() while true do end end) end\n"
      "end\n",
      "ctl.lua", limits);
  EXPECT_THROW(script.Step(0, Joints(1)), LuaScriptError);
}

TEST(LuaScript, MemoryLimitStopsARunawayTable) {
  LuaLimits limits;
  limits.memory_bytes = size_t{8} << 20;
  LuaScript script(
      "function step(t, state)\n"
      "  local big = {}\n"
      "  for i = 1, 1e9 do big[i] = i end\n"
      "end\n",
      "ctl.lua", limits);
  try {
    script.Step(0, Joints(1));
    FAIL() << "no error";
  } catch (const LuaScriptError& e) {
    EXPECT_NE(std::string(e.what()).find("memory"), std::string::npos)
        << e.what();
  }
  LuaScript rep("function step() return {#string.rep('x', 1e9)} end", "rep.lua",
                limits);
  EXPECT_THROW(rep.Step(0, Joints(1)), LuaScriptError);
}

TEST(LuaScript, SandboxHasNoFilesProcessesOrBytecode) {
  for (const char* name :
       {"io", "os", "package", "debug", "require", "dofile", "loadfile", "load",
        "coroutine", "collectgarbage", "string.dump"}) {
    const std::string source = std::string("function step() return {") + name +
                               " == nil and 1 or 0} end";
    LuaScript script(source, "ctl.lua");
    EXPECT_EQ(script.Step(0, Joints(1))[0], 1.0) << name;
  }
}

TEST(LuaScript, ResultOfTheWrongShapeIsAnErrorAtTheStepLine) {
  const char* bad[] = {
      "function step() return 1 end", "function step() return {1, 2} end",
      "function step() return {'a'} end", "function step() return {0/0} end",
      "function step() return {math.huge} end"};
  for (const char* source : bad) {
    LuaScript script(source, "ctl.lua");
    try {
      script.Step(0, Joints(1));
      ADD_FAILURE() << source;
    } catch (const LuaScriptError& e) {
      EXPECT_EQ(e.line(), 1) << e.what();
      EXPECT_NE(std::string(e.what()).find("step"), std::string::npos);
    }
  }
}

TEST(LuaScript, PrintIsCollectedNotWrittenAndRandomIsRepeatable) {
  LuaScript a("function step() print('hi', 2) return {math.random()} end",
              "a.lua");
  LuaScript b("function step() return {math.random()} end", "b.lua");
  EXPECT_EQ(a.Step(0, Joints(1)), b.Step(0, Joints(1)));
  EXPECT_EQ(a.TakePrinted(), (std::vector<std::string>{"hi\t2"}));
  EXPECT_TRUE(a.TakePrinted().empty());
}

TEST(LuaScript, TemplatesLoadAndMoveTheJoints) {
  ASSERT_GE(LuaTemplates().size(), 2u);
  for (const LuaTemplate& t : LuaTemplates()) {
    LuaScript script(t.source, t.name + ".lua");
    LuaRobotState s = Joints(8);
    for (int i = 0; i < 8; ++i) s.axes.push_back(i % 2 ? "yaw" : "pitch");
    double swing = 0;
    for (int k = 0; k < 300; ++k) {
      for (double a : script.Step(k * 0.01, s)) {
        ASSERT_TRUE(std::isfinite(a));
        swing = std::max(swing, std::abs(a));
      }
    }
    EXPECT_GT(swing, 0.1) << t.name;
  }
}

}  // namespace
}  // namespace mrsim

// The Run panel's controller choice in the real window under its own Xvfb:
// a Lua controller typed into the editor shows its syntax error with the
// line before Run; fixed, Run starts mrsim-lua and the robot moves.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "tests/common/child_process.h"
#include "tests/studio/studio_test_util.h"

namespace mrsim::testing {
namespace {

namespace fs = std::filesystem;

bool HaveX() {
  return fs::exists("/usr/bin/Xvfb") && fs::exists("/usr/bin/xdotool");
}

struct Live {
  double sim_time = -1;
  double com_x = 0;
  double com_y = 0;
};

Live ReadLive(const std::string& layout) {
  Live live;
  std::istringstream in(ReadLayout(layout)["live case_study"]);
  in >> live.sim_time >> live.com_x >> live.com_y;
  return live;
}

void Click(const std::string& layout, const std::string& widget) {
  int x = 0, y = 0;
  ASSERT_TRUE(
      WaitUntil([&] { return WidgetCentre(layout, widget, &x, &y); }, 60))
      << widget;
  ASSERT_TRUE(ClickAt(x, y));
}

// Empties the editor and types `first`, a new line and `second` into it.
// Return is held until the window has the new line (ImGui 1.86 misses a
// key pressed and released within one frame; characters are queued).
void TypeScript(const std::string& layout, const std::string& first,
                const std::string& second) {
  Click(layout, "Clear script");
  ASSERT_TRUE(WaitForLayout(layout, "lua lines", "1", 60));
  Click(layout, "lua editor");
  ASSERT_TRUE(WaitForLayout(layout, "active", "lua editor", 60));
  ASSERT_TRUE(Xdotool({"type", first}));
  ASSERT_TRUE(Xdotool({"keydown", "Return"}));
  const bool two = WaitForLayout(layout, "lua lines", "2", 60);
  ASSERT_TRUE(Xdotool({"keyup", "Return"}));
  ASSERT_TRUE(two);
  ASSERT_TRUE(Xdotool({"type", second}));
}

TEST(StudioLua, ScriptErrorShowsItsLineAndTheFixedScriptDrivesTheRobot) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string dir = TempDir("studio_lua_window");
  const std::string layout = dir + "/layout.txt";
  fs::copy_file(SourcePath("scenarios/case_study.xml"),
                dir + "/case_study.xml");
  XvfbDisplay xvfb(dir);
  ASSERT_TRUE(xvfb.ok());
  setenv("XDG_CONFIG_HOME", dir.c_str(), 1);
  setenv("LCM_DEFAULT_URL", TestLcmUrl(7944).c_str(), 1);
  ChildProcess studio(
      {"/bin/sh", "-c",
       "cd '" + dir + "' && exec '" + BinaryPath("studio/mrsim-studio") +
           "' --layout-dump layout.txt case_study.xml"},
      dir + "/studio.log");
  ASSERT_TRUE(WaitForLayout(layout, "revision", "0")) << studio.Output();
  ASSERT_TRUE(Xdotool({"key", "F5"}));
  Click(layout, "controller lua");
  ASSERT_TRUE(WaitForLayout(layout, "controller", "lua", 60));

  // An error on line 2: shown with its line, before any Run.
  ASSERT_NO_FATAL_FAILURE(
      TypeScript(layout, "function step(t, s)", "  return {t +} end"));
  ASSERT_TRUE(WaitForLayout(layout, "lua error line", "2", 60))
      << ReadLayout(layout)["lua error"];
  EXPECT_NE(ReadLayout(layout)["lua error"].find("controller.lua:2:"),
            std::string::npos);

  // Fixed: a travelling wave.
  ASSERT_NO_FATAL_FAILURE(TypeScript(
      layout, "function step(t, s)",
      "  local a = {} for i = 1, s.n do a[i] = 0.7 * math.sin(4 * t - i) "
      "end return a end"));
  ASSERT_TRUE(WaitForLayout(layout, "lua error", "", 60))
      << ReadLayout(layout)["lua error"];
  EXPECT_EQ(ReadLayout(layout)["lua error line"], "0");
  const std::string front = ReadLayout(layout)["part module 0 0"];

  Click(layout, "Run");
  ASSERT_TRUE(WaitUntil([&] { return ReadLive(layout).sim_time >= 0; }, 120))
      << studio.Output() << ReadLayout(layout)["live message"];
  const Live start = ReadLive(layout);
  ASSERT_TRUE(WaitUntil(
      [&] { return ReadLive(layout).sim_time >= start.sim_time + 3; }, 120))
      << studio.Output();
  const Live end = ReadLive(layout);
  EXPECT_GT(std::hypot(end.com_x - start.com_x, end.com_y - start.com_y), 0.005)
      << "the robot did not move";
  EXPECT_NE(ReadLayout(layout)["part module 0 0"], front);
  // The script ran as mrsim-lua would from the file beside the design.
  std::ifstream script(dir + "/case_study.controller.lua");
  std::stringstream text;
  text << script.rdbuf();
  EXPECT_NE(text.str().find("math.sin(4 * t - i)"), std::string::npos);

  // The script takes no steering: the Steering section says so, and an
  // arrow key says why at once rather than sending into "no answer".
  const auto steering = [&] { return ReadLayout(layout)["live steering"]; };
  EXPECT_TRUE(WaitUntil(
      [&] {
        return steering().rfind(
                   "off: robot 'case_study' is driven by your Lua script", 0) ==
               0;
      },
      60))
      << steering();
  ASSERT_TRUE(Xdotool({"key", "Up"}));
  EXPECT_TRUE(WaitUntil(
      [&] {
        return ReadLayout(layout)["live message"].find(
                   "driven by your Lua script") != std::string::npos;
      },
      60))
      << ReadLayout(layout)["live message"];
  EXPECT_EQ(ReadLayout(layout)["live request"], "") << "a steering request";

  Click(layout, "Stop");
  ASSERT_TRUE(WaitForLayout(layout, "live busy", "idle", 60));
  ASSERT_TRUE(Xdotool({"key", "ctrl+q"}));
  EXPECT_EQ(studio.Wait(90), 0) << studio.Output();
}

}  // namespace
}  // namespace mrsim::testing

// The studio's Run panel in the real window under its own Xvfb: Run starts
// the case study, a real Up key press drives it forward, Pause stops sim
// time and Step 10 advances it by 0.1 s.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
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
};

Live ReadLive(const std::string& layout) {
  Live live;
  std::istringstream in(ReadLayout(layout)["live case_study"]);
  in >> live.sim_time >> live.com_x;
  return live;
}

double StatusTime(const std::string& layout) {
  std::istringstream in(ReadLayout(layout)["live status"]);
  double t = -1;
  in >> t;
  return t;
}

void Click(const std::string& layout, const std::string& widget) {
  int x = 0, y = 0;
  ASSERT_TRUE(
      WaitUntil([&] { return WidgetCentre(layout, widget, &x, &y); }, 60))
      << widget;
  ASSERT_TRUE(ClickAt(x, y));
}

TEST(StudioRun, UpArrowDrivesForwardPauseStopsAndStepAdvancesATenth) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string dir = TempDir("studio_run_window");
  const std::string file = dir + "/case_study.xml";
  fs::copy_file(SourcePath("scenarios/case_study.xml"), file);
  const std::string layout = dir + "/layout.txt";
  XvfbDisplay xvfb(dir);
  ASSERT_TRUE(xvfb.ok());
  setenv("XDG_CONFIG_HOME", dir.c_str(), 1);
  // The panel's URL defaults to LCM_DEFAULT_URL: this test's own port.
  setenv("LCM_DEFAULT_URL", TestLcmUrl(7967).c_str(), 1);
  ChildProcess studio(
      {BinaryPath("studio/mrsim-studio"), "--layout-dump", layout, file},
      dir + "/studio.log");
  ASSERT_TRUE(WaitForLayout(layout, "revision", "0")) << studio.Output();

  const std::string front_as_designed = ReadLayout(layout)["part module 0 0"];
  ASSERT_FALSE(front_as_designed.empty());
  ASSERT_TRUE(Xdotool({"key", "F5"}));
  Click(layout, "Run");
  ASSERT_TRUE(WaitUntil([&] { return ReadLive(layout).sim_time >= 0; }, 120))
      << studio.Output();

  // Stop the robot (space), then a real Up key press sets it going.
  ASSERT_TRUE(Xdotool({"key", "space"}));
  ASSERT_TRUE(WaitForLayout(layout, "live gait", "stop", 60));
  const Live before = ReadLive(layout);
  ASSERT_TRUE(Xdotool({"key", "Up"}));
  ASSERT_TRUE(WaitForLayout(layout, "live gait", "forward", 60));
  ASSERT_TRUE(WaitUntil(
      [&] { return ReadLive(layout).sim_time >= before.sim_time + 4; }, 120));
  EXPECT_GT(ReadLive(layout).com_x - before.com_x, 0.02)
      << "the centre of mass did not move +x";
  // The 3-D view shows the robot where the simulation has it.
  EXPECT_NE(ReadLayout(layout)["part module 0 0"], front_as_designed);

  // Pause: acknowledged; then Step (10 periods by default) moves sim time
  // by exactly 0.1 s from where it stopped, and no further.
  Click(layout, "Pause");
  ASSERT_TRUE(WaitForLayout(layout, "live request", "pause: done", 60));
  ASSERT_TRUE(WaitUntil(
      [&] {
        return ReadLayout(layout)["live status"].find("paused") !=
               std::string::npos;
      },
      60));
  const double paused_at = StatusTime(layout);
  Click(layout, "Step");
  ASSERT_TRUE(WaitForLayout(layout, "live request", "step 10: done", 60));
  ASSERT_TRUE(WaitUntil(
      [&] { return ReadLive(layout).sim_time >= paused_at + 0.1 - 1e-9; }, 60));
  EXPECT_NEAR(ReadLive(layout).sim_time, paused_at + 0.1, 1e-9);

  Click(layout, "Stop");
  ASSERT_TRUE(Xdotool({"key", "ctrl+q"}));
  EXPECT_EQ(studio.Wait(90), 0) << studio.Output();
}

// Types `text` into the number field recorded as `widget`: a click selects
// its text whole (ImGui 1.86 loses a key pressed and released within one
// frame, so no ctrl+a; typed characters are queued and never lost).
void TypeInto(const std::string& layout, const std::string& widget,
              const std::string& text) {
  std::istringstream in(ReadLayout(layout)["widget " + widget]);
  int x = 0, y = 0, w = 0, h = 0;
  ASSERT_TRUE(in >> x >> y >> w >> h) << widget;
  ASSERT_TRUE(ClickAt(x + 15, y + h / 2));
  // Characters that arrive in the frame of the click go to the field still
  // active: type once the window says this one has taken the click.
  ASSERT_TRUE(WaitForLayout(layout, "active", widget, 60))
      << ReadLayout(layout)["active"];
  ASSERT_TRUE(Xdotool({"type", text}));
}

TEST(StudioRun, OptimisationFromTheWindowCompletesAndItsBestPlaysLive) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string dir = TempDir("studio_optimise_window");
  const std::string file = dir + "/case_study.xml";
  fs::copy_file(SourcePath("scenarios/case_study.xml"), file);
  const std::string layout = dir + "/layout.txt";
  XvfbDisplay xvfb(dir);
  ASSERT_TRUE(xvfb.ok());
  setenv("XDG_CONFIG_HOME", dir.c_str(), 1);
  setenv("LCM_DEFAULT_URL", TestLcmUrl(7968).c_str(), 1);
  // The studio runs in `dir`: its genome and output paths are relative.
  fs::create_directories(dir + "/scenarios");
  fs::copy_file(SourcePath("scenarios/forward_gait.genome.xml"),
                dir + "/scenarios/forward_gait.genome.xml");
  ChildProcess studio(
      {"/bin/sh", "-c",
       "cd '" + dir + "' && exec '" + BinaryPath("studio/mrsim-studio") +
           "' --layout-dump layout.txt case_study.xml"},
      dir + "/studio.log");
  ASSERT_TRUE(WaitForLayout(layout, "revision", "0")) << studio.Output();
  ASSERT_TRUE(Xdotool({"key", "F5"}));
  Click(layout, "Run");
  ASSERT_TRUE(WaitUntil([&] { return ReadLive(layout).sim_time >= 0; }, 120))
      << studio.Output();

  // Room for the Optimise section: fold the two open ones, each fold seen
  // in the layout before the next click (the widgets below it move).
  auto gone = [&](const std::string& widget) {
    return WaitUntil(
        [&] { return ReadLayout(layout).count("widget " + widget) == 0; }, 60);
  };
  Click(layout, "header Simulator");
  ASSERT_TRUE(gone("Reset"));
  Click(layout, "header Steering");
  ASSERT_TRUE(gone("sidewind-left"));
  Click(layout, "header Optimise");
  ASSERT_TRUE(WaitUntil(
      [&] { return ReadLayout(layout).count("widget generations") > 0; }, 60));
  // Each value seen in the window before the next click: characters and a
  // click arriving within one frame would go to the field still active.
  TypeInto(layout, "generations", "2");
  ASSERT_TRUE(WaitForLayout(layout, "optimise settings", "2 8 5", 60))
      << ReadLayout(layout)["optimise settings"];
  TypeInto(layout, "population", "4");
  ASSERT_TRUE(WaitForLayout(layout, "optimise settings", "2 4 5", 60))
      << ReadLayout(layout)["optimise settings"];
  TypeInto(layout, "episode", "1");
  ASSERT_TRUE(WaitForLayout(layout, "optimise settings", "2 4 1", 60))
      << ReadLayout(layout)["optimise settings"];
  Click(layout, "Start optimisation");
  if (!WaitUntil(
          [&] { return ReadLayout(layout)["optimise"] != "0 of 0 idle"; },
          60)) {
    std::system(("import -window root '" + dir + "/start_failed.png'").c_str());
  }
  ASSERT_TRUE(WaitForLayout(layout, "optimise", "2 of 2 finished", 300))
      << ReadLayout(layout)["optimise"] << "\n"
      << ReadLayout(layout)["live message"] << "\n"
      << studio.Output();
  EXPECT_TRUE(fs::exists(dir + "/optimise/generations.csv"));

  auto watching = [&](const std::string& start) {
    return WaitUntil(
        [&] {
          return ReadLayout(layout)["optimise watching"].rfind(start, 0) == 0;
        },
        60);
  };
  Click(layout, "Watch best");
  ASSERT_TRUE(
      WaitForLayout(layout, "live request", "case_study parameters: done", 60))
      << ReadLayout(layout)["live request"];
  EXPECT_TRUE(watching("playing generation "))
      << ReadLayout(layout)["optimise watching"];

  // Jump to generation 1 (the field's default): the run has it, so its
  // best plays at once.
  Click(layout, "Jump to generation");
  EXPECT_TRUE(watching("playing generation 1's best"))
      << ReadLayout(layout)["optimise watching"] << "\n"
      << ReadLayout(layout)["live message"];
  EXPECT_EQ(ReadLayout(layout)["optimise"], "2 of 2 finished");

  Click(layout, "Stop");
  ASSERT_TRUE(Xdotool({"key", "ctrl+q"}));
  EXPECT_EQ(studio.Wait(90), 0) << studio.Output();
}

}  // namespace
}  // namespace mrsim::testing

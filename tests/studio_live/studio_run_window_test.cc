// The studio's Run panel in the real window under its own Xvfb: Run starts
// the case study, a real Up key press drives it forward, Pause stops sim
// time and Step 10 advances it by 0.1 s; a design with a head camera shows
// the camera's picture live.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdint>
#include <cstdlib>
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
};

Live ReadLive(const std::string& layout,
              const std::string& robot = "case_study") {
  Live live;
  std::istringstream in(ReadLayout(layout)["live " + robot]);
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

// The studio on a copy of the case study in its own directory, display,
// settings and LCM port, started from that directory (the Optimise
// panel's paths are relative to it) and running: Run pressed, states heard.
class StudioRun : public ::testing::Test {
 protected:
  // `scenario` (from the source tree) runs; `robot` is heard.
  void OpenAndRun(const std::string& name, int port,
                  const std::string& scenario = "scenarios/case_study.xml",
                  const std::string& robot = "case_study") {
    dir_ = TempDir(name);
    layout_ = dir_ + "/layout.txt";
    const std::string file = fs::path(scenario).filename().string();
    fs::copy_file(SourcePath(scenario), dir_ + "/" + file);
    // The Optimise panel's default genome, relative to where it runs.
    fs::create_directories(dir_ + "/scenarios");
    fs::copy_file(SourcePath("scenarios/forward_gait.genome.xml"),
                  dir_ + "/scenarios/forward_gait.genome.xml");
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok());
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);
    // The panel's URL defaults to LCM_DEFAULT_URL: this test's own port.
    setenv("LCM_DEFAULT_URL", TestLcmUrl(port).c_str(), 1);
    studio_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{
            "/bin/sh", "-c",
            "cd '" + dir_ + "' && exec '" + BinaryPath("studio/mrsim-studio") +
                "' --layout-dump layout.txt '" + file + "'"},
        dir_ + "/studio.log");
    ASSERT_TRUE(WaitForLayout(layout_, "revision", "0")) << studio_->Output();
    front_as_designed_ = ReadLayout(layout_)["part module 0 0"];
    ASSERT_FALSE(front_as_designed_.empty());
    ASSERT_TRUE(Xdotool({"key", "F5"}));
    Click(layout_, "Run");
    ASSERT_TRUE(
        WaitUntil([&] { return ReadLive(layout_, robot).sim_time >= 0; }, 120))
        << studio_->Output();
  }

  std::string dir_, layout_, front_as_designed_;
  std::unique_ptr<XvfbDisplay> xvfb_;
  std::unique_ptr<ChildProcess> studio_;
};

TEST_F(StudioRun, UpArrowDrivesForwardPauseStopsAndStepAdvancesATenth) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(OpenAndRun("studio_run_window", 7967));
  const std::string& layout = layout_;
  ChildProcess& studio = *studio_;

  // Stop the robot (space), then a real Up key press sets it going.
  ASSERT_TRUE(Xdotool({"key", "space"}));
  ASSERT_TRUE(WaitForLayout(layout, "live gait", "stop", 60));
  // mrsim-gait's status says it takes steering: the section offers it.
  EXPECT_EQ(ReadLayout(layout)["live steering"], "on");
  const Live before = ReadLive(layout);
  ASSERT_TRUE(Xdotool({"key", "Up"}));
  ASSERT_TRUE(WaitForLayout(layout, "live gait", "forward", 60));
  ASSERT_TRUE(WaitUntil(
      [&] { return ReadLive(layout).sim_time >= before.sim_time + 4; }, 120));
  EXPECT_GT(ReadLive(layout).com_x - before.com_x, 0.02)
      << "the centre of mass did not move +x";
  // The 3-D view shows the robot where the simulation has it.
  EXPECT_NE(ReadLayout(layout)["part module 0 0"], front_as_designed_);

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

  // Quitting while it runs asks first; Cancel keeps everything going.
  ASSERT_TRUE(Xdotool({"key", "ctrl+q"}));
  ASSERT_TRUE(WaitForLayout(layout, "modal", "busy", 60));
  Click(layout, "busy Cancel");
  ASSERT_TRUE(WaitForLayout(layout, "modal", "none", 60));
  EXPECT_TRUE(studio.running());

  Click(layout, "Stop");
  // Stopped: now it quits without asking.
  ASSERT_TRUE(WaitForLayout(layout, "live busy", "idle", 60))
      << ReadLayout(layout)["live busy"];
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

TEST_F(StudioRun, OptimisationFromTheWindowCompletesAndItsBestPlaysLive) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(OpenAndRun("studio_optimise_window", 7968));
  const std::string& dir = dir_;
  const std::string& layout = layout_;
  ChildProcess& studio = *studio_;

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
  // The window's fitness and algorithm settings reached mrsim-opt (its
  // checkpoint records every setting of the run).
  {
    std::ifstream in(dir + "/optimise/checkpoint.txt");
    std::stringstream text;
    text << in.rdbuf();
    for (const char* line :
         {"setting distance_mode=forward", "setting w_distance=1",
          "setting cmaes_sigma=0.3"}) {
      EXPECT_NE(text.str().find(line), std::string::npos) << line;
    }
  }

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

  // A click in the frames right after the best's run restarted can be
  // lost (seen under Xvfb, not understood yet): Stop is clicked again until
  // the panel says nothing runs. Then it quits without asking.
  bool idle = false;
  for (int attempt = 0; attempt < 3 && !idle; ++attempt) {
    Click(layout, "Stop");
    idle = WaitForLayout(layout, "live busy", "idle", 20);
  }
  ASSERT_TRUE(idle) << ReadLayout(layout)["live busy"];

  // Save keeps the Optimise form in the design (<optimization>): reopened,
  // or given to mrsim-opt, it runs this setup.
  ASSERT_TRUE(Xdotool({"key", "ctrl+s"}));
  const auto saved = [&] {
    std::ifstream in(dir + "/case_study.xml");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  };
  EXPECT_TRUE(WaitUntil(
      [&] {
        return saved().find("<generations>2</generations>") !=
               std::string::npos;
      },
      60))
      << ReadLayout(layout)["message"];
  for (const char* field :
       {"<population>4</population>", "<episode>1</episode>",
        "<algorithm>cmaes</algorithm>", "<genome>"}) {
    EXPECT_NE(saved().find(field), std::string::npos) << field;
  }
  ASSERT_TRUE(Xdotool({"key", "ctrl+q"}));
  EXPECT_EQ(studio.Wait(90), 0) << studio.Output();
}

// A design with a head camera: while it runs, the Run panel's Camera
// section shows the camera's picture of the states the studio hears,
// rendered again as sim time passes frames.
TEST_F(StudioRun, TheCameraSectionShowsTheHeadCameraLive) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(OpenAndRun("studio_camera_window", 7982,
                                     "scenarios/camera_snake.xml",
                                     "camera_snake"));
  EXPECT_EQ(ReadLayout(layout_)["camera cameras"], "1");
  int x = 0, y = 0;
  ASSERT_TRUE(WaitUntil(
      [&] { return WidgetCentre(layout_, "camera picture", &x, &y); }, 120))
      << studio_->Output();
  // A picture of a state heard (seq >= 0), then newer ones.
  std::int64_t first = -1;
  ASSERT_TRUE(WaitUntil(
      [&] {
        first = std::atoll(ReadLayout(layout_)["camera seq"].c_str());
        return first >= 0;
      },
      120))
      << studio_->Output();
  ASSERT_TRUE(WaitUntil(
      [&] {
        return std::atoll(ReadLayout(layout_)["camera seq"].c_str()) > first;
      },
      120))
      << studio_->Output();
}

}  // namespace
}  // namespace mrsim::testing

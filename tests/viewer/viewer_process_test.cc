// mrsim-view as a real process: replaying an .lcmlog, listening to a live
// LCM stream published by the test, joining late, stopping on SIGTERM,
// refusing bad input.
#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/viewer/viewer_test_util.h"
#include "viewer/camera_control.h"
#include "viewer/frame_writer.h"
#include "viewer/gl_context.h"
#include "viewer/renderer.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;
using testing::BinaryPath;
using testing::ChildProcess;
using testing::TempDir;
using testing::TestLcmUrl;

const std::string kViewer = "viewer/process/mrsim-view";

std::vector<unsigned char> Encode(const RobotState& state, int64_t seq) {
  robot_state_t msg = ToRobotStateMessage(state, seq);
  std::vector<unsigned char> bytes(msg.getEncodedSize());
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// "done: N frames (R rendered, first index K, ..."
bool ParseSummary(const std::string& output, int64_t* frames,
                  int64_t* first_index, int64_t* malformed) {
  std::smatch m;
  const std::regex re(
      "done: (\\d+) frames \\((\\d+) rendered, first index (-?\\d+).*, "
      "(\\d+) states, (\\d+) malformed");
  if (!std::regex_search(output, m, re)) return false;
  *frames = std::stoll(m[1]);
  *first_index = std::stoll(m[3]);
  *malformed = std::stoll(m[5]);
  return true;
}

TEST(ViewerProcess, LogReplayGivesOneFramePerStepAndFramesMove) {
  const std::string dir = TempDir("viewer_log_replay");
  const Scenario scenario = testing::ViewerTestScenario();
  const std::string scenario_path = testing::WriteTestScenario(scenario, dir);
  Physics physics(ReadScenarioFile(scenario_path));

  // 2 s of a moving snake, a state every 10 ms, plus junk to be dropped.
  const std::string log_path = dir + "/states.lcmlog";
  const std::string channel = StateChannel("MRSIM", "snake");
  int64_t first_utime = -1;
  int64_t last_utime = -1;
  {
    lcm::LogFile log(log_path, "w");
    ASSERT_TRUE(log.good());
    int64_t event = 0;
    auto write = [&](const std::string& ch, std::vector<unsigned char> data,
                     int64_t utime) {
      lcm::LogEvent ev;
      ev.eventnum = event++;
      ev.timestamp = utime;
      ev.channel = ch;
      ev.datalen = static_cast<int32_t>(data.size());
      ev.data = data.data();
      ASSERT_EQ(log.writeEvent(&ev), 0);
    };
    for (int k = 1; k <= 200; ++k) {
      testing::DriveTo(&physics, k * 0.01);
      const RobotState state = physics.ReadRobotState(0);
      const int64_t utime = SimTimeToUtime(state.time);
      if (first_utime < 0) first_utime = utime;
      last_utime = utime;
      write(channel, Encode(state, k), utime);
      if (k == 50) write(channel, {1, 2, 3, 4, 5}, utime);  // malformed
      if (k == 60) write("OTHER_CHANNEL", {9, 9}, utime);   // ignored
    }
  }
  const double fps = 20.0;
  int64_t expected = 0;
  for (int64_t k = 0; k * 50000 <= last_utime; ++k) {
    if (k * 50000 >= first_utime) ++expected;
  }
  ASSERT_GT(expected, 30);

  const std::string video = dir + "/replay.mp4";
  ChildProcess viewer({BinaryPath(kViewer), scenario_path, "--from-log",
                       log_path, "--out", video, "--fps", "20", "--width",
                       "320", "--height", "240", "--overlay", "wave"},
                      dir + "/viewer.log");
  ASSERT_EQ(viewer.Wait(90.0), 0) << viewer.Output();
  int64_t frames = 0, first_index = 0, malformed = 0;
  ASSERT_TRUE(ParseSummary(viewer.Output(), &frames, &first_index, &malformed))
      << viewer.Output();
  EXPECT_EQ(frames, expected);
  EXPECT_EQ(malformed, 1);
  (void)fps;

  cv::VideoCapture capture(video);
  ASSERT_TRUE(capture.isOpened());
  std::vector<cv::Mat> images;
  cv::Mat image;
  while (capture.read(image)) images.push_back(image.clone());
  ASSERT_EQ(static_cast<int64_t>(images.size()), expected);
  EXPECT_EQ(images[0].cols, 320);
  EXPECT_EQ(images[0].rows, 240);
  int changed = 0;
  for (size_t i = 0; i < images.size(); ++i) {
    EXPECT_GT(testing::GreyStdDev(images[i]), 5.0) << "blank frame " << i;
    if (i > 0 && testing::MeanAbsDiff(images[i], images[i - 1]) > 0.2) {
      ++changed;
    }
  }
  // The robot moves all the time, so nearly every frame differs.
  EXPECT_GT(changed, static_cast<int>(images.size()) * 3 / 4);
  EXPECT_GT(testing::MeanAbsDiff(images.front(), images.back()), 1.0);
}

TEST(ViewerProcess, LiveFrameMatchesFrameRenderedInProcess) {
  const std::string dir = TempDir("viewer_live_match");
  const std::string frames_dir = dir + "/frames";
  const std::string url = TestLcmUrl(7801);
  const std::string scenario_path =
      testing::WriteTestScenario(testing::ViewerTestScenario(), dir);
  std::vector<std::string> args = {
      BinaryPath(kViewer), scenario_path, "--lcm-url",    url,
      "--frames-dir",      frames_dir,    "--fps",        "10",
      "--overlay",         "test wave",   "--max-frames", "3"};
  for (const std::string& f : testing::FixedViewFlags()) args.push_back(f);
  ChildProcess viewer(args, dir + "/viewer.log");
  ASSERT_TRUE(viewer.WaitForOutput("listening", 30.0)) << viewer.Output();

  GlContext gl;
  Physics physics(ReadScenarioFile(scenario_path));
  const ViewerOptions view = testing::FixedView();
  Renderer renderer(physics.model(), view.width, view.height, view.quality);
  const CameraSettings settings = view.camera;
  CameraControl camera(settings);

  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  std::vector<cv::Mat> expected;
  for (int k = 0; k < 3; ++k) {
    testing::DriveTo(&physics, k * 0.1);
    const RobotState state = physics.ReadRobotState(0);
    Overlay overlay;
    overlay.time = state.time;
    overlay.speed = state.com_velocity.norm();
    overlay.gait = "test wave";
    cv::Mat image;
    renderer.Render(physics.mutable_data(), camera.camera(),
                    testing::PhysicsRays(physics, state), &overlay, &image);
    expected.push_back(image);
    // The viewer keeps a history of states (--queue), so they need no
    // pacing: each frame shows the newest state at or before its time.
    const robot_state_t msg = ToRobotStateMessage(state, k);
    lcm.publish(StateChannel("MRSIM", "snake"), &msg);
  }
  // One more state past frame 2's time so it is due, repeated until the
  // viewer has its three frames and stops.
  testing::DriveTo(&physics, 0.25);
  const robot_state_t last = ToRobotStateMessage(physics.ReadRobotState(0), 3);
  int code = -1;
  testing::RepeatUntil(
      [&] { lcm.publish(StateChannel("MRSIM", "snake"), &last); },
      [&] { return (code = viewer.Wait(0)) != -1; }, 0.1, 30.0);
  ASSERT_EQ(code, 0) << viewer.Output();
  for (int k = 0; k < 3; ++k) {
    const std::string file = FrameWriter::PngName(frames_dir, k);
    const cv::Mat frame = cv::imread(file);
    ASSERT_FALSE(frame.empty()) << file << "\n" << viewer.Output();
    cv::imwrite(dir + "/expected_" + std::to_string(k) + ".png", expected[k]);
    EXPECT_LT(testing::MeanAbsDiff(frame, expected[k]), 1.0)
        << file << " vs " << dir << "/expected_" << k << ".png";
  }
  EXPECT_GT(testing::MeanAbsDiff(expected[0], expected[2]), 1.0);
}

TEST(ViewerProcess, LateJoinerShowsNewestStateAndSigtermLeavesPlayableVideo) {
  const std::string dir = TempDir("viewer_late_join");
  const std::string url = TestLcmUrl(7802);
  const std::string scenario_path =
      testing::WriteTestScenario(testing::ViewerTestScenario(), dir);

  // The "simulator": about real time, a state every 20 ms of sim time.
  std::atomic<bool> stop{false};
  std::atomic<double> sim_time{0.0};
  std::thread publisher([&] {
    lcm::LCM lcm(url);
    Physics physics(ReadScenarioFile(scenario_path));
    int64_t seq = 0;
    testing::RepeatUntil(
        [&] {
          testing::DriveTo(&physics, physics.time() + 0.02);
          const robot_state_t msg =
              ToRobotStateMessage(physics.ReadRobotState(0), seq++);
          lcm.publish(StateChannel("MRSIM", "snake"), &msg);
          sim_time = physics.time();
        },
        [&] { return stop.load(); }, 0.02, 300.0);
  });
  ASSERT_TRUE(testing::WaitUntil([&] { return sim_time >= 1.0; }, 60.0));
  const double joined_at = sim_time;
  const std::string video = dir + "/late.mp4";
  ChildProcess viewer(
      {BinaryPath(kViewer), scenario_path, "--lcm-url", url, "--out", video,
       "--fps", "10", "--width", "160", "--height", "120"},
      dir + "/viewer.log");
  const bool listening = viewer.WaitForOutput("listening", 30.0);
  const double listening_at = sim_time;
  // A second of simulation for it to see: ten frames at 10 fps.
  testing::WaitUntil(
      [&] { return !listening || sim_time >= listening_at + 1.0; }, 60.0);
  viewer.Signal(SIGTERM);
  const int code = viewer.Wait(30.0);
  stop = true;
  publisher.join();
  ASSERT_TRUE(listening) << viewer.Output();
  ASSERT_EQ(code, 0) << viewer.Output();

  int64_t frames = 0, first_index = 0, malformed = 0;
  ASSERT_TRUE(ParseSummary(viewer.Output(), &frames, &first_index, &malformed))
      << viewer.Output();
  // It starts at what the simulator was doing when it joined, not at 0.
  EXPECT_GE(first_index, static_cast<int64_t>(std::floor(joined_at * 10)));
  EXPECT_GE(frames, 3);
  EXPECT_EQ(malformed, 0);
  cv::VideoCapture capture(video);
  ASSERT_TRUE(capture.isOpened()) << "video not playable after SIGTERM";
  int64_t read = 0;
  cv::Mat image;
  while (capture.read(image)) ++read;
  EXPECT_EQ(read, frames);
}

// Asked for a video with no simulator on the network: stopped, it says
// nothing was written and why, and fails (a launch or script must not
// take the missing video for a success).
TEST(ViewerProcess, NoStateHeardIsNothingWrittenAndAFailure) {
  const std::string dir = TempDir("viewer_no_state");
  const std::string scenario_path =
      testing::WriteTestScenario(testing::ViewerTestScenario(), dir);
  const std::string video = dir + "/none.mp4";
  ChildProcess viewer(
      {BinaryPath(kViewer), scenario_path, "--lcm-url", TestLcmUrl(7805),
       "--out", video, "--width", "160", "--height", "120"},
      dir + "/viewer.log");
  ASSERT_TRUE(viewer.WaitForOutput("listening", 30.0)) << viewer.Output();
  viewer.Signal(SIGINT);
  EXPECT_EQ(viewer.Wait(30.0), 1) << viewer.Output();
  EXPECT_NE(viewer.Output().find(
                "nothing written: no state arrived on MRSIM_STATE_snake"),
            std::string::npos)
      << viewer.Output();
  EXPECT_FALSE(std::filesystem::exists(video));
}

TEST(ViewerProcess, RendersTheStreamOfTheRealSimulator) {
  const std::string dir = TempDir("viewer_with_sim");
  const std::string url = TestLcmUrl(7804);
  const std::string scenario_path =
      testing::WriteTestScenario(testing::ViewerTestScenario(), dir);
  const std::string video = dir + "/sim.mp4";
  // 2 s of simulation at 10 frames/s hold at least 19 whole frames (the
  // first state may come after 0): the viewer stops by itself after them.
  constexpr int64_t kFrames = 19;
  ChildProcess viewer(
      {BinaryPath(kViewer), scenario_path, "--lcm-url", url, "--out", video,
       "--fps", "10", "--width", "160", "--height", "120", "--max-frames",
       std::to_string(kFrames)},
      dir + "/viewer.log");
  ASSERT_TRUE(viewer.WaitForOutput("listening", 30.0)) << viewer.Output();
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"), scenario_path,
                    "--lcm-url", url, "--clock", "realtime", "--speed", "4",
                    "--rate", "50", "--duration", "2"},
                   dir + "/sim.log");
  ASSERT_EQ(sim.Wait(60.0), 0) << sim.Output();
  ASSERT_EQ(viewer.Wait(30.0), 0) << viewer.Output();
  int64_t frames = 0, first_index = 0, malformed = 0;
  ASSERT_TRUE(ParseSummary(viewer.Output(), &frames, &first_index, &malformed))
      << viewer.Output();
  EXPECT_EQ(malformed, 0) << viewer.Output();
  EXPECT_EQ(frames, kFrames) << viewer.Output();
  cv::VideoCapture capture(video);
  ASSERT_TRUE(capture.isOpened());
  int64_t read = 0;
  cv::Mat image;
  while (capture.read(image)) {
    EXPECT_GT(testing::GreyStdDev(image), 5.0);
    ++read;
  }
  EXPECT_EQ(read, frames);
}

// Writes a short .lcmlog of the moving test snake; returns its path.
std::string WriteMovingLog(const std::string& dir,
                           const std::string& scenario_path, int states) {
  Physics physics(ReadScenarioFile(scenario_path));
  const std::string path = dir + "/states.lcmlog";
  lcm::LogFile log(path, "w");
  for (int k = 1; k <= states; ++k) {
    testing::DriveTo(&physics, k * 0.02);
    const RobotState state = physics.ReadRobotState(0);
    std::vector<unsigned char> data = Encode(state, k);
    lcm::LogEvent ev;
    ev.eventnum = k;
    ev.timestamp = SimTimeToUtime(state.time);
    ev.channel = StateChannel("MRSIM", "snake");
    ev.datalen = static_cast<int32_t>(data.size());
    ev.data = data.data();
    log.writeEvent(&ev);
  }
  return path;
}

// A virtual display: Xvfb picks a free display (-displayfd) and writes its
// number once it accepts connections. Returns ":N", or "" when it did not
// start.
std::string StartXvfb(ChildProcess& xvfb) {
  std::string display;
  testing::WaitUntil(
      [&] {
        std::smatch m;
        const std::string out = xvfb.Output();
        if (std::regex_search(out, m, std::regex(R"((^|\n)(\d+)\n)"))) {
          display = ":" + m[2].str();
        }
        return !display.empty() || !xvfb.running();
      },
      60.0);
  return display;
}

std::vector<std::string> XvfbArgs() {
  return {"/usr/bin/Xvfb", "-displayfd", "1",  "-screen", "0",
          "640x480x24",    "-nolisten",  "tcp"};
}

TEST(ViewerProcess, WindowOnVirtualDisplayWritesTheSameFramesAsHeadless) {
  if (!std::filesystem::exists("/usr/bin/Xvfb")) {
    GTEST_SKIP() << "Xvfb not installed (scripts/install_deps.sh)";
  }
  const std::string dir = TempDir("viewer_window");
  const std::string scenario_path =
      testing::WriteTestScenario(testing::ViewerTestScenario(), dir);
  const std::string log = WriteMovingLog(dir, scenario_path, 25);
  ChildProcess xvfb(XvfbArgs(), dir + "/xvfb.log");
  const std::string display = StartXvfb(xvfb);
  ASSERT_FALSE(display.empty()) << "Xvfb did not start: " << xvfb.Output();
  const std::vector<std::string> common = {
      scenario_path, "--from-log", log,   "--fps",        "10", "--width",
      "160",         "--height",   "120", "--max-frames", "4"};
  std::vector<std::string> windowed = {"/usr/bin/env", "DISPLAY=" + display,
                                       BinaryPath(kViewer)};
  windowed.insert(windowed.end(), common.begin(), common.end());
  windowed.insert(windowed.end(),
                  {"--window", "--frames-dir", dir + "/window"});
  std::vector<std::string> headless = {"/usr/bin/env", "-u", "DISPLAY",
                                       BinaryPath(kViewer)};
  headless.insert(headless.end(), common.begin(), common.end());
  headless.insert(headless.end(), {"--frames-dir", dir + "/headless"});
  {
    ChildProcess viewer(windowed, dir + "/window.log");
    ASSERT_EQ(viewer.Wait(60.0), 0) << viewer.Output();
    EXPECT_NE(viewer.Output().find("window context"), std::string::npos)
        << viewer.Output();
  }
  {
    ChildProcess viewer(headless, dir + "/headless.log");
    ASSERT_EQ(viewer.Wait(60.0), 0) << viewer.Output();
  }
  for (int k = 1; k <= 4; ++k) {
    const cv::Mat a = cv::imread(FrameWriter::PngName(dir + "/window", k));
    const cv::Mat b = cv::imread(FrameWriter::PngName(dir + "/headless", k));
    ASSERT_FALSE(a.empty());
    ASSERT_FALSE(b.empty());
    EXPECT_GT(testing::GreyStdDev(a), 5.0);
    EXPECT_LT(testing::MeanAbsDiff(a, b), 1.0) << "frame " << k;
  }
}

// The window answers whatever the render rate: with the simulator running
// as fast as it can, frames fall behind at once, and a real key press (X
// events from xdotool) still quits the viewer. It used to drain every due
// frame before looking at the window, so `q` did nothing.
TEST(ViewerProcess, WindowAnswersQWhileRenderingFallsBehind) {
  if (!std::filesystem::exists("/usr/bin/Xvfb") ||
      !std::filesystem::exists("/usr/bin/xdotool")) {
    GTEST_SKIP() << "Xvfb or xdotool not installed (scripts/install_deps.sh)";
  }
  const std::string dir = TempDir("viewer_window_input");
  const std::string url = TestLcmUrl(7806);
  const std::string scenario = testing::SourcePath("scenarios/snake11.xml");
  ChildProcess xvfb(XvfbArgs(), dir + "/xvfb.log");
  const std::string display = StartXvfb(xvfb);
  ASSERT_FALSE(display.empty()) << "Xvfb did not start: " << xvfb.Output();
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"), scenario,
                    "--lcm-url", url, "--clock", "fast"},
                   dir + "/sim.log");
  ChildProcess viewer(
      {"/usr/bin/env", "DISPLAY=" + display, BinaryPath(kViewer), scenario,
       "--lcm-url", url, "--window", "--fps", "200", "--width", "640",
       "--height", "480"},
      dir + "/viewer.log");
  ASSERT_TRUE(viewer.WaitForOutput("listening", 60.0)) << viewer.Output();
  // Rendering and behind: the fast simulator's states reach the viewer.
  ASSERT_TRUE(testing::WaitUntil(
      [&] {
        ChildProcess probe(
            {"/usr/bin/env", "DISPLAY=" + display, "/usr/bin/xdotool", "search",
             "--name", "mrsim-view"},
            dir + "/search.log");
        return probe.Wait(30.0) == 0;
      },
      60.0))
      << viewer.Output();
  ASSERT_TRUE(sim.running()) << sim.Output();
  // Focus it (no window manager: xdotool sets the input focus) and press q
  // through XTEST, as a keyboard would.
  ChildProcess press(
      {"/usr/bin/env", "DISPLAY=" + display, "/usr/bin/xdotool", "search",
       "--name", "mrsim-view", "windowfocus", "%1", "key", "q"},
      dir + "/press.log");
  EXPECT_EQ(press.Wait(30.0), 0) << press.Output();
  EXPECT_EQ(viewer.Wait(10.0), 0) << viewer.Output();
  EXPECT_NE(viewer.Output().find("mrsim-view: done"), std::string::npos)
      << viewer.Output();
  sim.Stop();
}

TEST(ViewerProcess, BadScenarioExitsWithTwoAndNamesTheFile) {
  const std::string dir = TempDir("viewer_bad_input");
  const std::string bad = dir + "/broken.xml";
  {
    std::FILE* f = std::fopen(bad.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("<Scenario><robot><modules>", f);
    std::fclose(f);
  }
  ChildProcess viewer({BinaryPath(kViewer), bad, "--frames-dir", dir + "/f"},
                      dir + "/viewer.log");
  EXPECT_EQ(viewer.Wait(30.0), 2);
  EXPECT_NE(viewer.Output().find("broken.xml"), std::string::npos)
      << viewer.Output();
  ChildProcess no_output({BinaryPath(kViewer), bad}, dir + "/viewer2.log");
  EXPECT_EQ(no_output.Wait(30.0), 2);
  const std::string good =
      testing::WriteTestScenario(testing::ViewerTestScenario(), dir);
  ChildProcess bad_lookat({BinaryPath(kViewer), good, "--frames-dir",
                           dir + "/f", "--lookat", "1,2"},
                          dir + "/viewer3.log");
  EXPECT_EQ(bad_lookat.Wait(30.0), 2);
  EXPECT_NE(bad_lookat.Output().find("--lookat"), std::string::npos)
      << bad_lookat.Output();
  ChildProcess bad_robot({BinaryPath(kViewer), good, "--frames-dir", dir + "/f",
                          "--robot", "nobody"},
                         dir + "/viewer4.log");
  EXPECT_EQ(bad_robot.Wait(30.0), 2);
  EXPECT_NE(bad_robot.Output().find("nobody"), std::string::npos)
      << bad_robot.Output();
}

TEST(ViewerProcess, WindowWithoutDisplayExitsTwoAndWritesNothing) {
  const std::string dir = TempDir("viewer_no_display");
  const std::string scenario =
      testing::WriteTestScenario(testing::ViewerTestScenario(), dir);
  ChildProcess viewer(
      {"/usr/bin/env", "-u", "DISPLAY", "-u", "WAYLAND_DISPLAY",
       BinaryPath("viewer/process/mrsim-view"), scenario, "--window", "--out",
       dir + "/v.mp4", "--lcm-url", testing::TestLcmUrl(7840)},
      dir + "/viewer.log");
  EXPECT_EQ(viewer.Wait(30.0), 2);
  EXPECT_NE(viewer.Output().find("--window: no display"), std::string::npos)
      << viewer.Output();
  EXPECT_FALSE(fs::exists(dir + "/v.mp4"));
}

TEST(ViewerProcess, FromLogThatIsNotALogOrOfAnotherRobotFailsWritingNothing) {
  const std::string dir = TempDir("viewer_bad_log");
  const std::string scenario =
      testing::WriteTestScenario(testing::ViewerTestScenario(), dir);
  std::ofstream(dir + "/notes.txt") << "not an LCM log at all\n";
  ChildProcess not_log(
      {BinaryPath("viewer/process/mrsim-view"), scenario, "--from-log",
       dir + "/notes.txt", "--out", dir + "/a.mp4"},
      dir + "/a.log");
  EXPECT_EQ(not_log.Wait(30.0), 2);
  EXPECT_NE(not_log.Output().find("notes.txt: not an LCM log"),
            std::string::npos)
      << not_log.Output();
  EXPECT_FALSE(fs::exists(dir + "/a.mp4"));

  // A log of a robot with another number of modules: every state is
  // malformed for this scenario.
  ChainOptions chain;
  chain.name = "snake";
  chain.modules = 3;
  Scenario other;
  other.robots.push_back(MakeChain(chain));
  const std::string other_dir = TempDir("viewer_bad_log_other");
  const std::string other_path = testing::WriteTestScenario(other, other_dir);
  Physics physics(ReadScenarioFile(other_path));
  {
    lcm::LogFile log(dir + "/other.lcmlog", "w");
    for (int k = 1; k <= 5; ++k) {
      testing::DriveTo(&physics, k * 0.05);
      robot_state_t msg = ToRobotStateMessage(physics.ReadRobotState(0), k);
      std::vector<unsigned char> data(msg.getEncodedSize());
      msg.encode(data.data(), 0, static_cast<int>(data.size()));
      lcm::LogEvent ev;
      ev.eventnum = k;
      ev.timestamp = k * 50000;
      ev.channel = "MRSIM_STATE_" + other.robots[0].name;
      ev.datalen = static_cast<int32_t>(data.size());
      ev.data = data.data();
      log.writeEvent(&ev);
    }
  }
  ChildProcess mismatch(
      {BinaryPath("viewer/process/mrsim-view"), scenario, "--from-log",
       dir + "/other.lcmlog", "--out", dir + "/b.mp4"},
      dir + "/b.log");
  EXPECT_EQ(mismatch.Wait(30.0), 2);
  EXPECT_NE(mismatch.Output().find("no state of the scenario's robots"),
            std::string::npos)
      << mismatch.Output();
  EXPECT_FALSE(fs::exists(dir + "/b.mp4"));
}

}  // namespace
}  // namespace mrsim

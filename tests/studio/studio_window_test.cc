// The real mrsim-studio under its own Xvfb, driven by OS-level input
// (xdotool), and its off-screen screenshot.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/studio/studio_test_util.h"

namespace mrsim::testing {
namespace {

namespace fs = std::filesystem;

std::string Studio() { return BinaryPath("studio/mrsim-studio"); }

bool HaveX() {
  return fs::exists("/usr/bin/Xvfb") && fs::exists("/usr/bin/xdotool");
}

// The studio in a window on a private display, with its layout dump.
class StudioWindowTest : public ::testing::Test {
 protected:
  void Start(const std::string& name, const std::string& scenario,
             const std::vector<std::string>& flags = {}) {
    dir_ = TempDir(name);
    layout_ = dir_ + "/layout.txt";
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok()) << "Xvfb did not start, see " << dir_;
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);  // recent files stay here
    std::vector<std::string> argv = {Studio(), "--layout-dump", layout_};
    argv.insert(argv.end(), flags.begin(), flags.end());
    if (!scenario.empty()) argv.push_back(scenario);
    studio_ = std::make_unique<ChildProcess>(argv, dir_ + "/studio.log");
    ASSERT_TRUE(WaitForLayout(layout_, "revision", "0")) << studio_->Output();
  }

  // Clicks a widget by name and waits for the preview's revision to reach
  // `revision` (each edit is one rebuild).
  void ClickAndWait(const std::string& widget, int revision) {
    int x = 0, y = 0;
    ASSERT_TRUE(WidgetCentre(layout_, widget, &x, &y)) << widget;
    ASSERT_TRUE(ClickAt(x, y));
    ASSERT_TRUE(WaitForLayout(layout_, "revision", std::to_string(revision)))
        << "after clicking " << widget << ": "
        << ReadLayout(layout_)["message"];
  }

  std::string dir_;
  std::string layout_;
  std::unique_ptr<XvfbDisplay> xvfb_;
  std::unique_ptr<ChildProcess> studio_;
};

TEST_F(StudioWindowTest, ClicksBuildARobotThatSavesAndSelectsIn3D) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  Start("studio_window_build", "");
  const std::string file = dir_ + "/robot.xml";
  studio_->Stop();
  studio_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{Studio(), "--layout-dump", layout_, file},
      dir_ + "/studio2.log");
  ASSERT_TRUE(WaitForLayout(layout_, "path", file));
  ClickAndWait("pitch module", 1);
  ClickAndWait("pitch module", 2);
  ClickAndWait("yaw module", 3);
  ClickAndWait("ball", 4);
  int x = 0, y = 0;
  ASSERT_TRUE(WidgetCentre(layout_, "Save", &x, &y));
  ASSERT_TRUE(ClickAt(x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "dirty", "0")) << studio_->Output();

  const Scenario saved = ReadScenarioFile(file);  // validates
  ASSERT_EQ(saved.robots.size(), 1u);
  EXPECT_EQ(saved.robots[0].modules.size(), 3u);
  EXPECT_EQ(saved.robots[0].modules[2].axis, Axis::kYaw);
  ASSERT_EQ(saved.scene_objects.size(), 1u);
  EXPECT_EQ(saved.scene_objects[0].shape, PrimitiveShape::kSphere);

  // The ball is selected; a click on module 1 in the 3-D view selects it.
  EXPECT_EQ(ReadLayout(layout_)["selected"], "object 0 0");
  std::istringstream where(ReadLayout(layout_)["part module 0 1"]);
  ASSERT_TRUE(where >> x >> y) << "module 1 not on screen";
  ASSERT_TRUE(ClickAt(x, y));
  EXPECT_TRUE(WaitForLayout(layout_, "selected", "module 0 1"))
      << ReadLayout(layout_)["selected"];
  studio_->Stop();
}

TEST_F(StudioWindowTest, ClosingWithUnsavedChangesAsksFirst) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string dir = TempDir("studio_window_close_src");
  const std::string file = dir + "/case_study.xml";
  fs::copy_file(SourcePath("scenarios/case_study.xml"), file);
  Start("studio_window_close", file);
  ClickAndWait("box", 1);
  ASSERT_TRUE(WaitForLayout(layout_, "dirty", "1"));
  // A refused button action says so in a dialog, not only in the top bar:
  // the box is selected, and removing module 0 would leave two sensor
  // modules side by side.
  int x = 0, y = 0;
  std::istringstream front(ReadLayout(layout_)["part module 0 0"]);
  ASSERT_TRUE(front >> x >> y);
  ASSERT_TRUE(ClickAt(x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "module 0 0"));
  ASSERT_TRUE(WidgetCentre(layout_, "Remove", &x, &y));
  ASSERT_TRUE(ClickAt(x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "modal", "refused"))
      << ReadLayout(layout_)["message"];
  ASSERT_TRUE(WidgetCentre(layout_, "refused OK", &x, &y));
  ASSERT_TRUE(ClickAt(x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "modal", "none"));
  ASSERT_TRUE(Xdotool({"key", "ctrl+q"}));
  ASSERT_TRUE(WaitForLayout(layout_, "modal", "unsaved"));
  EXPECT_TRUE(studio_->running()) << "quit without asking";
  ASSERT_TRUE(WidgetCentre(layout_, "unsaved Discard", &x, &y));
  ASSERT_TRUE(ClickAt(x, y));
  EXPECT_EQ(studio_->Wait(90), 0) << studio_->Output();
  std::ifstream a(file), b(SourcePath("scenarios/case_study.xml"));
  std::stringstream sa, sb;
  sa << a.rdbuf();
  sb << b.rdbuf();
  EXPECT_TRUE(sa.str() == sb.str()) << "the file changed without Save";
}

// A rectangle "x y w h" of the layout dump.
struct Box {
  double x = 0, y = 0, w = 0, h = 0;
  double right() const { return x + w; }
  double bottom() const { return y + h; }
  bool Holds(const Box& b) const {
    return b.x >= x - 0.5 && b.right() <= right() + 0.5 && b.y >= y - 0.5 &&
           b.bottom() <= bottom() + 0.5;
  }
};

Box ParseBox(const std::string& text) {
  Box b;
  std::istringstream in(text);
  in >> b.x >> b.y >> b.w >> b.h;
  return b;
}

// A copy of the case study in its own folder (videos go beside it).
std::string CaseStudyCopy(const std::string& name) {
  const std::string dir = TempDir(name);
  const std::string file = dir + "/case_study.xml";
  fs::copy_file(SourcePath("scenarios/case_study.xml"), file,
                fs::copy_options::overwrite_existing);
  return file;
}

TEST_F(StudioWindowTest, TabAndShiftTabHideThePanelsForAFullWindowView) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  Start("studio_window_panels", CaseStudyCopy("studio_window_panels_src"));
  const auto before = ReadLayout(layout_);
  ASSERT_NE(before.at("panel left"), "hidden");
  ASSERT_NE(before.at("panel right"), "hidden");
  // Keys go to the window under the pointer.
  ASSERT_TRUE(Xdotool({"mousemove", "640", "400"}));
  ASSERT_TRUE(Xdotool({"key", "Tab"}));
  ASSERT_TRUE(WaitForLayout(layout_, "panel left", "hidden"));
  EXPECT_NE(ReadLayout(layout_)["panel right"], "hidden");
  ASSERT_TRUE(Xdotool({"key", "shift+Tab"}));
  ASSERT_TRUE(WaitForLayout(layout_, "panel right", "hidden"));
  // The 3-D view fills the window under the status bar.
  const Box view = ParseBox(ReadLayout(layout_)["panel view"]);
  EXPECT_EQ(view.x, 0);
  EXPECT_EQ(view.w, 1280);
  EXPECT_EQ(view.bottom(), 800);
  // F11 brings both back; again hides both.
  ASSERT_TRUE(Xdotool({"key", "F11"}));
  ASSERT_TRUE(WaitForLayout(layout_, "panel left", before.at("panel left")));
  EXPECT_TRUE(WaitForLayout(layout_, "panel right", before.at("panel right")));
  ASSERT_TRUE(Xdotool({"key", "F11"}));
  EXPECT_TRUE(WaitForLayout(layout_, "panel left", "hidden"));
  EXPECT_TRUE(WaitForLayout(layout_, "panel right", "hidden"));
  studio_->Stop();
}

TEST_F(StudioWindowTest, At1024By640NoPanelsOverlap) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  Start("studio_window_small", CaseStudyCopy("studio_window_small_src"),
        {"--width", "1024", "--height", "640", "--ui-scale", "1"});
  ASSERT_TRUE(WaitForLayout(layout_, "ui scale", "1.00"));
  auto l = ReadLayout(layout_);
  const Box left = ParseBox(l["panel left"]),
            right = ParseBox(l["panel right"]);
  const Box view = ParseBox(l["panel view"]),
            status = ParseBox(l["panel status"]);
  const Box window{0, 0, 1024, 640};
  for (const Box& b : {left, right, view, status}) {
    EXPECT_TRUE(window.Holds(b)) << b.x << " " << b.y << " " << b.w;
  }
  EXPECT_LE(left.right(), view.x);
  EXPECT_LE(view.right(), right.x);
  EXPECT_GE(view.w, 300) << "the 3-D view squeezed out";
  // The buttons sit inside their own panel.
  for (const char* name : {"Save", "Save As", "Help (F1)"}) {
    int x = 0, y = 0;
    ASSERT_TRUE(WidgetCentre(layout_, name, &x, &y)) << name;
    EXPECT_TRUE(left.Holds(ParseBox(l[std::string("widget ") + name])))
        << name << " " << l[std::string("widget ") + name];
  }
  for (const char* name : {"Run panel (F5)", "View"}) {
    EXPECT_TRUE(status.Holds(ParseBox(l[std::string("widget ") + name])))
        << name << " " << l[std::string("widget ") + name];
  }
  // The Run panel in the right column fits too.
  ASSERT_TRUE(Xdotool({"mousemove", "500", "400"}));
  ASSERT_TRUE(Xdotool({"key", "F5"}));
  ASSERT_TRUE(WaitUntil(
      [&] { return ReadLayout(layout_).count("widget Run") > 0; }, 60));
  l = ReadLayout(layout_);
  EXPECT_TRUE(right.Holds(ParseBox(l["widget Run"]))) << l["widget Run"];
  studio_->Stop();
}

// At 1280x800 the Run panel's Optimise header is on screen without
// scrolling, and opened, so is its Start button.
TEST_F(StudioWindowTest, At1280By800OptimiseIsReachableWithoutScrolling) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  Start("studio_window_optimise_reach",
        CaseStudyCopy("studio_window_optimise_reach_src"),
        {"--width", "1280", "--height", "800"});
  ASSERT_TRUE(Xdotool({"mousemove", "640", "400"}));
  ASSERT_TRUE(Xdotool({"key", "F5"}));
  ASSERT_TRUE(WaitUntil(
      [&] { return ReadLayout(layout_).count("widget header Optimise") > 0; },
      60));
  auto l = ReadLayout(layout_);
  const Box window{0, 0, 1280, 800};
  const Box right = ParseBox(l["panel right"]);
  ASSERT_TRUE(window.Holds(right)) << l["panel right"];
  const Box header = ParseBox(l["widget header Optimise"]);
  EXPECT_TRUE(right.Holds(header)) << l["widget header Optimise"];
  ASSERT_NO_FATAL_FAILURE(
      ClickWhenThere(layout_, static_cast<int>(header.x + header.w / 2),
                     static_cast<int>(header.y + header.h / 2)));
  ASSERT_TRUE(WaitUntil(
      [&] {
        return ReadLayout(layout_).count("widget Start optimisation") > 0;
      },
      60));
  l = ReadLayout(layout_);
  EXPECT_TRUE(right.Holds(ParseBox(l["widget Start optimisation"])))
      << l["widget Start optimisation"];
  studio_->Stop();
}

TEST_F(StudioWindowTest, RecordsThreeSecondsOfTheViewToAPlayableMp4) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string file = CaseStudyCopy("studio_window_video_src");
  Start("studio_window_video", file);
  ASSERT_TRUE(Xdotool({"mousemove", "640", "400"}));
  // The recording lies inside [before the start key, after the stop is
  // seen]: the video's length must too, whatever the load.
  const auto before_start = std::chrono::steady_clock::now();
  ASSERT_TRUE(Xdotool({"key", "ctrl+r"}));
  ASSERT_TRUE(WaitForLayout(layout_, "video", "recording"))
      << ReadLayout(layout_)["message"];
  // The video's own clock says when 3 s are in it.
  ASSERT_TRUE(WaitUntil(
      [&] {
        const std::string s = ReadLayout(layout_)["video seconds"];
        return !s.empty() && std::stod(s) >= 3.0;
      },
      120));
  ASSERT_TRUE(Xdotool({"key", "ctrl+r"}));
  ASSERT_TRUE(WaitForLayout(layout_, "video", "stopped"));
  const double recorded_at_most =
      std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                    before_start)
          .count();
  const std::string video = ReadLayout(layout_)["video last"];
  ASSERT_EQ(fs::path(video).parent_path(), fs::path(file).parent_path());
  ASSERT_TRUE(fs::exists(video)) << video;
  // Listed with its size: the note names the file and its megabytes.
  const std::string note = ReadLayout(layout_)["message"];
  EXPECT_NE(note.find(video), std::string::npos) << note;
  EXPECT_TRUE(note.find("MB") != std::string::npos ||
              note.find("kB") != std::string::npos)
      << note;

  cv::VideoCapture in(video, cv::CAP_FFMPEG);
  ASSERT_TRUE(in.isOpened()) << video;
  const double fps = in.get(cv::CAP_PROP_FPS);
  const double frames = in.get(cv::CAP_PROP_FRAME_COUNT);
  ASSERT_NEAR(fps, 30, 0.5);
  // 3 s, plus the time the stop key took to arrive (one frame of slack).
  EXPECT_GE(frames / fps, 2.95);
  EXPECT_LE(frames / fps, recorded_at_most + 1.0 / 30);
  const int fourcc = static_cast<int>(in.get(cv::CAP_PROP_FOURCC));
  const std::string codec = {static_cast<char>(fourcc & 255),
                             static_cast<char>((fourcc >> 8) & 255),
                             static_cast<char>((fourcc >> 16) & 255),
                             static_cast<char>((fourcc >> 24) & 255)};
  EXPECT_TRUE(codec == "avc1" || codec == "h264") << codec;
  int decoded = 0;
  cv::Mat frame, last;
  while (in.read(frame)) {
    ++decoded;
    last = frame.clone();
  }
  EXPECT_NEAR(decoded, frames, 2) << "not every frame decodes";
  // The 3-D view alone: narrower than the window, as tall as the view.
  EXPECT_GT(last.cols, 300);
  EXPECT_LT(last.cols, 1280 - 600);
  EXPECT_GT(last.rows, 600);
  studio_->Stop();
}

TEST(StudioScreenshot, ShowsTheRobotAndThePanels) {
  const std::string dir = TempDir("studio_screenshot");
  const std::string png = dir + "/studio.png";
  unsetenv("DISPLAY");
  ChildProcess studio(
      {Studio(), "--screenshot", png, SourcePath("scenarios/case_study.xml")},
      dir + "/studio.log");
  ASSERT_EQ(studio.Wait(180), 0) << studio.Output();
  const cv::Mat image = cv::imread(png);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 1280);
  EXPECT_EQ(image.rows, 800);
  // Panels: dark backgrounds left and right with text (not uniform).
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::Scalar mean, dev;
  cv::meanStdDev(grey(cv::Rect(0, 0, 300, 700)), mean, dev);
  EXPECT_LT(mean[0], 90) << "left panel not dark";
  EXPECT_GT(dev[0], 15) << "left panel empty";
  cv::meanStdDev(grey(cv::Rect(900, 0, 370, 700)), mean, dev);
  EXPECT_GT(dev[0], 15) << "inspector empty";
  // The 3-D view shows the robot: orange (pitch) and blue (yaw) modules.
  cv::Mat hsv;
  cv::cvtColor(image(cv::Rect(340, 40, 530, 750)), hsv, cv::COLOR_BGR2HSV);
  cv::Mat orange, blue;
  cv::inRange(hsv, cv::Scalar(10, 150, 120), cv::Scalar(25, 255, 255), orange);
  cv::inRange(hsv, cv::Scalar(100, 150, 120), cv::Scalar(115, 255, 255), blue);
  EXPECT_GT(cv::countNonZero(orange), 200) << "no pitch module in view";
  EXPECT_GT(cv::countNonZero(blue), 200) << "no yaw module in view";
}

TEST(StudioCli, WithoutADisplayItSaysSoAndExits2) {
  const std::string dir = TempDir("studio_cli");
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  ChildProcess studio({Studio()}, dir + "/studio.log");
  EXPECT_EQ(studio.Wait(60), 2);
  EXPECT_NE(studio.Output().find("no display"), std::string::npos)
      << studio.Output();
  ChildProcess version({Studio(), "--version"}, dir + "/version.log");
  EXPECT_EQ(version.Wait(60), 0);
  EXPECT_NE(version.Output().find("mrsim-studio"), std::string::npos);
  ChildProcess bad({Studio(), SourcePath("scenarios/terrain.png")},
                   dir + "/bad.log");
  EXPECT_EQ(bad.Wait(60), 2) << bad.Output();
}

}  // namespace
}  // namespace mrsim::testing

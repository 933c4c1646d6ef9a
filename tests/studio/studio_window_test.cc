// The real mrsim-studio under its own Xvfb, driven by OS-level input
// (xdotool), and its off-screen screenshot.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "sim_core/scenario_xml.h"
#include "tests/common/child_process.h"
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
  void Start(const std::string& name, const std::string& scenario) {
    dir_ = TempDir(name);
    layout_ = dir_ + "/layout.txt";
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok()) << "Xvfb did not start, see " << dir_;
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);  // recent files stay here
    studio_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{Studio(), "--layout-dump", layout_, scenario},
        dir_ + "/studio.log");
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

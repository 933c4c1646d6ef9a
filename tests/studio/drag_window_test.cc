// Drag and drop in the real mrsim-studio under its own Xvfb, with real mouse
// and key events (xdotool): reorder the chain by dragging a row, drop a
// module from the palette into the chain, drag the ball 0.3 m with the move
// handle and turn the robot a quarter with the heading ring; the saved file
// has the parts where they were dropped.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

#include "sim_core/scenario/scenario_xml.h"
#include "studio/design/chain_edit.h"
#include "studio/design/ground_move.h"
#include "tests/common/child_process.h"
#include "tests/studio/studio_test_util.h"

namespace mrsim::testing {
namespace {

namespace fs = std::filesystem;

bool HaveX() {
  return fs::exists("/usr/bin/Xvfb") && fs::exists("/usr/bin/xdotool");
}

// A "x y" layout value.
bool Point(const std::string& layout, const std::string& key, int* x, int* y) {
  std::istringstream in(ReadLayout(layout)[key]);
  double fx = 0, fy = 0;
  if (!(in >> fx >> fy)) return false;
  *x = static_cast<int>(std::lround(fx));
  *y = static_cast<int>(std::lround(fy));
  return true;
}

// A widget's rectangle (left, top, width, height).
bool Rect(const std::string& layout, const std::string& name, int r[4]) {
  std::istringstream in(ReadLayout(layout)["widget " + name]);
  return static_cast<bool>(in >> r[0] >> r[1] >> r[2] >> r[3]);
}

class StudioDragWindow : public ::testing::Test {
 protected:
  void Start(const std::string& name, const std::string& scenario) {
    dir_ = TempDir(name);
    layout_ = dir_ + "/layout.txt";
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok()) << "Xvfb did not start, see " << dir_;
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);
    studio_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{BinaryPath("studio/mrsim-studio"),
                                 "--layout-dump", layout_, scenario},
        dir_ + "/studio.log");
    ASSERT_TRUE(WaitForLayout(layout_, "path", scenario)) << studio_->Output();
  }

  void ClickAndWait(const std::string& widget, const std::string& key,
                    const std::string& value) {
    int x = 0, y = 0;
    ASSERT_TRUE(WidgetCentre(layout_, widget, &x, &y)) << widget;
    ASSERT_TRUE(ClickAt(x, y));
    ASSERT_TRUE(WaitForLayout(layout_, key, value))
        << "after clicking " << widget << ": " << ReadLayout(layout_)[key]
        << " " << ReadLayout(layout_)["message"];
  }

  void Drag(int x0, int y0, int x1, int y1, const std::string& key,
            const std::string& started) {
    ASSERT_TRUE(DragOnScreen(layout_, x0, y0, x1, y1, key, started))
        << key << ": " << ReadLayout(layout_)[key] << ", mouse "
        << ReadLayout(layout_)["mouse"];
  }

  void Save() {
    ASSERT_TRUE(Xdotool({"key", "ctrl+s"}));
    ASSERT_TRUE(WaitForLayout(layout_, "dirty", "0"))
        << ReadLayout(layout_)["message"];
  }

  std::string dir_;
  std::string layout_;
  std::unique_ptr<XvfbDisplay> xvfb_;
  std::unique_ptr<ChildProcess> studio_;
};

TEST_F(StudioDragWindow, ReorderByDragAndDropAModuleFromThePalette) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string file = TempDir("studio_drag_chain_src") + "/robot.xml";
  Start("studio_drag_chain", file);
  ClickAndWait("pitch module", "revision", "1");
  ClickAndWait("pitch module", "revision", "2");
  ClickAndWait("yaw module", "revision", "3");
  // The yaw module (place 2) dragged onto the upper half of the first row.
  int from[4], to[4];
  ASSERT_TRUE(Rect(layout_, "row module 0 2", from));
  ASSERT_TRUE(Rect(layout_, "row module 0 0", to));
  Drag(from[0] + 40, from[1] + from[3] / 2, to[0] + 40, to[1] + 2, "drag",
       "part 0 2");
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "4"))
      << ReadLayout(layout_)["message"];
  // A sensor module from the palette onto the lower half of the first row:
  // between the yaw module and the first pitch module.
  int palette[4];
  ASSERT_TRUE(Rect(layout_, "sensor module", palette));
  ASSERT_TRUE(Rect(layout_, "row module 0 0", to));
  Drag(palette[0] + palette[2] / 2, palette[1] + palette[3] / 2, to[0] + 40,
       to[1] + to[3] - 3, "drag", "new");
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "5"))
      << ReadLayout(layout_)["message"];
  Save();

  const Scenario saved = ReadScenarioFile(file);
  ASSERT_EQ(saved.robots.size(), 1u);
  std::string kinds;
  for (const studio::ChainSlot& s : studio::ChainOrder(saved.robots[0])) {
    kinds += s.sensor ? 'S' : s.axis == Axis::kPitch ? 'P' : 'Y';
  }
  EXPECT_EQ(kinds, "YSPP");
  // The front stays where module 0's hinge was.
  studio_->Stop();
}

// An empty design has no robot to drop onto: a module dropped anywhere in
// the 3-D view starts one.
TEST_F(StudioDragWindow, AModuleDroppedIntoAnEmptyDesignStartsARobot) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string file = TempDir("studio_drag_empty_src") + "/robot.xml";
  Start("studio_drag_empty", file);
  int palette[4], view[4];
  ASSERT_TRUE(Rect(layout_, "yaw module", palette));
  std::istringstream in(ReadLayout(layout_)["panel view"]);
  ASSERT_TRUE(in >> view[0] >> view[1] >> view[2] >> view[3]);
  Drag(palette[0] + palette[2] / 2, palette[1] + palette[3] / 2,
       view[0] + view[2] / 2, view[1] + view[3] / 2, "drag", "new");
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "1"))
      << ReadLayout(layout_)["message"];
  EXPECT_EQ(ReadLayout(layout_)["selected"], "module 0 0");
  Save();
  const Scenario saved = ReadScenarioFile(file);
  ASSERT_EQ(saved.robots.size(), 1u);
  ASSERT_EQ(saved.robots[0].modules.size(), 1u);
  EXPECT_EQ(saved.robots[0].modules[0].axis, Axis::kYaw);
  studio_->Stop();
}

TEST_F(StudioDragWindow, DragTheBallAndTurnTheRobotOnTheGround) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string file =
      TempDir("studio_drag_ground_src") + "/case_study.xml";
  fs::copy_file(SourcePath("scenarios/case_study.xml"), file);
  const Scenario before = ReadScenarioFile(file);
  ASSERT_FALSE(before.scene_objects.empty());
  Start("studio_drag_ground", file);
  ClickAndWait("row object 0", "selected", "object 0 0");
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  ASSERT_TRUE(Point(layout_, "handle move", &x0, &y0));
  ASSERT_TRUE(Point(layout_, "handle +0.3x", &x1, &y1));
  Drag(x0, y0, x1, y1, "handle drag", "move");
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "1"))
      << ReadLayout(layout_)["message"];

  ClickAndWait("row robot 0", "selected", "robot 0 0");
  ASSERT_TRUE(Point(layout_, "handle turn", &x0, &y0));
  ASSERT_TRUE(Point(layout_, "handle turn+90", &x1, &y1));
  Drag(x0, y0, x1, y1, "handle drag", "turn");
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "2"))
      << ReadLayout(layout_)["message"];
  Save();

  const Scenario saved = ReadScenarioFile(file);  // validates
  const Eigen::Vector3d moved =
      saved.scene_objects[0].position - before.scene_objects[0].position;
  EXPECT_NEAR(moved.x(), 0.3, 0.01);
  EXPECT_NEAR(moved.y(), 0.0, 0.01);
  EXPECT_NEAR(moved.z(), 0.0, 1e-9);
  const double turned = studio::RobotHeading(saved.robots[0]) -
                        studio::RobotHeading(before.robots[0]);
  EXPECT_NEAR(turned * 180 / M_PI, 90.0, 2.0);
  // Turned about its own centre: it stays where it was.
  EXPECT_LT((studio::RobotPivot(saved.robots[0]) -
             studio::RobotPivot(before.robots[0]))
                .norm(),
            1e-6);
  studio_->Stop();
}

}  // namespace
}  // namespace mrsim::testing

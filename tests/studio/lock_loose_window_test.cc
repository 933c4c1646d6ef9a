// Locks and loose parts from the real mrsim-studio under its own Xvfb,
// clicked and typed with real events (xdotool), as a student would: a
// lock picked in the design tree gets a breaking force, a loop lock is
// attached and detached, loose parts are added, edited, removed, joined
// and moved.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <sstream>

#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/studio/studio_test_util.h"

namespace mrsim::testing {
namespace {

namespace fs = std::filesystem;

bool HaveX() {
  return fs::exists("/usr/bin/Xvfb") && fs::exists("/usr/bin/xdotool");
}

class StudioLockLooseWindow : public ::testing::Test {
 protected:
  void Start(const std::string& name, const std::string& scenario,
             const std::vector<std::string>& flags = {}) {
    dir_ = TempDir(name);
    file_ = dir_ + "/design.xml";
    fs::copy_file(SourcePath(scenario), file_);
    layout_ = dir_ + "/layout.txt";
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok()) << "Xvfb did not start, see " << dir_;
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);
    std::vector<std::string> argv = {BinaryPath("studio/mrsim-studio"),
                                     "--layout-dump", layout_};
    argv.insert(argv.end(), flags.begin(), flags.end());
    argv.push_back(file_);
    studio_ = std::make_unique<ChildProcess>(argv, dir_ + "/studio.log");
    ASSERT_TRUE(WaitForLayout(layout_, "revision", "0")) << studio_->Output();
  }

  // Clicks the widget recorded as `widget` once it is on screen.
  void Click(const std::string& widget) {
    int x = 0, y = 0;
    ASSERT_TRUE(
        WaitUntil([&] { return WidgetCentre(layout_, widget, &x, &y); }, 90))
        << widget << " never shown";
    ASSERT_TRUE(ClickWhenThere(layout_, x, y)) << widget;
  }

  // Scrolls the Design panel's parts list to its end (the wheel over its
  // first row), so `widget`, a row below its fold, is shown.
  void ScrollPartsTo(const std::string& widget) {
    int x = 0, y = 0, rx = 0, ry = 0;
    ASSERT_TRUE(
        WaitUntil([&] { return WidgetCentre(layout_, widget, &x, &y); }, 90))
        << widget << " never listed";
    ASSERT_TRUE(WidgetCentre(layout_, "row robot 0", &rx, &ry));
    const std::string xs = std::to_string(rx), ys = std::to_string(ry);
    ASSERT_TRUE(Xdotool({"mousemove", xs, ys}));
    ASSERT_TRUE(WaitForLayout(layout_, "mouse", xs + " " + ys));
    ASSERT_TRUE(Xdotool({"click", "--repeat", "10", "--delay", "50", "5"}));
    // A row shown already (the list at its end) does not move.
    int now_x = 0, now_y = y;
    WaitUntil(
        [&] {
          return WidgetCentre(layout_, widget, &now_x, &now_y) && now_y < y;
        },
        10);
  }

  void ClickAndWait(const std::string& widget, int revision) {
    ASSERT_NO_FATAL_FAILURE(Click(widget));
    ASSERT_TRUE(WaitForLayout(layout_, "revision", std::to_string(revision)))
        << widget << ": " << ReadLayout(layout_)["message"];
  }

  // As the inspector tests type: click, type, Return held until taken.
  void TypeAndEnter(const std::string& widget, const std::string& text,
                    int revision) {
    ASSERT_NO_FATAL_FAILURE(Click(widget));
    ASSERT_TRUE(WaitForLayout(layout_, "active", widget))
        << ReadLayout(layout_)["active"];
    ASSERT_TRUE(Xdotool({"type", text}));
    ASSERT_TRUE(Xdotool({"keydown", "Return"}));
    const bool taken =
        WaitForLayout(layout_, "revision", std::to_string(revision));
    ASSERT_TRUE(Xdotool({"keyup", "Return"}));
    ASSERT_TRUE(taken) << ReadLayout(layout_)["message"];
    ASSERT_TRUE(
        WaitUntil([&] { return ReadLayout(layout_).count("active") == 0; }, 90))
        << ReadLayout(layout_)["active"];
  }

  Scenario Save() {
    Click("Save");
    EXPECT_TRUE(WaitForLayout(layout_, "dirty", "0"))
        << ReadLayout(layout_)["message"];
    return ReadScenarioFile(file_);
  }

  std::string dir_;
  std::string file_;
  std::string layout_;
  std::unique_ptr<XvfbDisplay> xvfb_;
  std::unique_ptr<ChildProcess> studio_;
};

// A lock picked in the design tree shows its breaking force, which is
// typed and saved; its Detach is refused (it holds the chain together)
// with the reason on the message line.
TEST_F(StudioLockLooseWindow, ALockPickedInTheTreeTakesABreakingForce) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(
      Start("studio_lock_break", "scenarios/case_study.xml"));
  ASSERT_NO_FATAL_FAILURE(ScrollPartsTo("row lock 0 1"));
  ASSERT_NO_FATAL_FAILURE(Click("row lock 0 1"));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "lock 0 1"));
  ASSERT_NO_FATAL_FAILURE(TypeAndEnter("field /breakForce", "25", 1));
  ASSERT_NO_FATAL_FAILURE(Click("Detach"));
  ASSERT_TRUE(WaitUntil(
      [&] {
        return ReadLayout(layout_)["message"].find(
                   "holds the chain together") != std::string::npos;
      },
      90))
      << ReadLayout(layout_)["message"];
  ASSERT_TRUE(WaitForLayout(layout_, "modal", "refused"));
  ASSERT_NO_FATAL_FAILURE(Click("refused OK"));
  ASSERT_TRUE(WaitForLayout(layout_, "modal", "none"));
  const Scenario saved = Save();
  EXPECT_EQ(saved.robots.at(0).locks.at(1).break_force, 25);
  const Scenario original =
      ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  EXPECT_EQ(saved.robots.at(0).locks.size(),
            original.robots.at(0).locks.size());
  studio_->Stop();
}

// From a selected module, "Attach lock" joins its front frame to a part
// it is not joined to (a loop lock); Detach takes it off again.
TEST_F(StudioLockLooseWindow, ALoopLockIsAttachedAndDetached) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(Start("studio_lock_loop", "scenarios/case_study.xml",
                                {"--select", "module 0"}));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "module 0 0"));
  const Scenario original = ReadScenarioFile(file_);
  const size_t locks = original.robots.at(0).locks.size();
  ASSERT_NO_FATAL_FAILURE(Click("header Attach lock"));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("Attach", 1));
  ASSERT_TRUE(
      WaitForLayout(layout_, "selected", "lock 0 " + std::to_string(locks)));
  Scenario saved = Save();
  ASSERT_EQ(saved.robots.at(0).locks.size(), locks + 1);
  EXPECT_EQ(saved.robots.at(0).locks.back().left_frame_guid,
            original.robots.at(0).modules.at(0).frames[0].guid);
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("Detach", 2));
  saved = Save();
  EXPECT_EQ(saved.robots.at(0).locks, original.robots.at(0).locks);
  studio_->Stop();
}

// "Add loose part..." puts a hinge (two loose frames and their joint)
// beside the robot; a frame picked in the tree takes a typed mass; Remove
// takes the other frame and the joint naming it.
TEST_F(StudioLockLooseWindow, LoosePartsAreAddedEditedAndRemoved) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(
      Start("studio_loose_parts", "scenarios/case_study.xml"));
  ASSERT_NO_FATAL_FAILURE(Click("Add loose part..."));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("loose hinge (two frames)", 1));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "loose_joint 0 0"));
  ASSERT_NO_FATAL_FAILURE(ScrollPartsTo("row loose_frame 1"));
  ASSERT_NO_FATAL_FAILURE(Click("row loose_frame 1"));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "loose_frame 0 1"));
  ASSERT_NO_FATAL_FAILURE(TypeAndEnter("field /mass", "0.3", 2));
  // The list is at its end already.
  ASSERT_NO_FATAL_FAILURE(Click("row loose_frame 0"));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "loose_frame 0 0"));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("Remove", 3));
  const Scenario saved = Save();
  ASSERT_EQ(saved.loose_frames.size(), 1u);
  EXPECT_EQ(saved.loose_frames[0].mass, 0.3);
  EXPECT_TRUE(saved.loose_joints.empty());
  studio_->Stop();
}

// A lock is drawn as a marker on top of the parts it joins, and a click
// on it in the 3-D view selects it, as its row in the Design panel does.
TEST_F(StudioLockLooseWindow, ALockIsPickedByClickingItInTheView) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(
      Start("studio_lock_pick", "scenarios/case_study.xml"));
  int x = 0, y = 0;
  ASSERT_TRUE(WaitUntil(
      [&] {
        std::istringstream in(ReadLayout(layout_)["part lock 0 1"]);
        return static_cast<bool>(in >> x >> y);
      },
      90))
      << "no lock marker in the view";
  ASSERT_TRUE(ClickWhenThere(layout_, x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "lock 0 1"))
      << ReadLayout(layout_)["selected"];
  studio_->Stop();
}

// A loose hinge's inspector has the servo switch: ticked, the servo's
// gains appear, a typed gain is taken, and Save writes both; the saved
// file reads back with the hinge driven.
TEST_F(StudioLockLooseWindow, ALooseHingeGetsAServoTickedAndSaved) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(
      Start("studio_loose_servo", "scenarios/case_study.xml"));
  ASSERT_NO_FATAL_FAILURE(Click("Add loose part..."));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("loose hinge (two frames)", 1));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "loose_joint 0 0"));
  // Passive: the gains are not offered until the servo is on.
  int x = 0, y = 0;
  ASSERT_TRUE(WaitUntil(
      [&] { return WidgetCentre(layout_, "field /servo", &x, &y); }, 90));
  EXPECT_FALSE(WidgetCentre(layout_, "field /Kp", &x, &y));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("field /servo", 2));
  ASSERT_NO_FATAL_FAILURE(TypeAndEnter("field /Kp", "4", 3));
  const Scenario saved = Save();
  ASSERT_EQ(saved.loose_joints.size(), 1u);
  EXPECT_TRUE(saved.loose_joints[0].servo);
  EXPECT_EQ(saved.loose_joints[0].kp, 4);
  EXPECT_EQ(saved.loose_joints[0].type, JointType::kHinge);
  studio_->Stop();
}

// A loose sensor module is locked to a loose frame the student picks in
// "Join to a loose part", and the two are dragged across the ground as
// one by the move handle: Save writes the lock and both moved 0.3 m.
TEST_F(StudioLockLooseWindow,
       ALooseSensorModuleIsLockedToALooseFrameAndMovedWithIt) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(
      Start("studio_loose_join", "scenarios/case_study.xml"));
  ASSERT_NO_FATAL_FAILURE(Click("Add loose part..."));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("loose frame", 1));
  ASSERT_NO_FATAL_FAILURE(Click("Add loose part..."));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("loose sensor module", 2));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "loose_sensor_module 0 0"));
  ASSERT_NO_FATAL_FAILURE(Click("header Join to a loose part"));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("Join with a lock", 3));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "loose_joint 0 0"));
  const Scenario joined = Save();
  ASSERT_EQ(joined.loose_joints.size(), 1u);
  EXPECT_EQ(joined.loose_joints[0].type, JointType::kLock);
  EXPECT_EQ(joined.loose_joints[0].left_frame_guid,
            joined.loose_sensor_modules.at(0).guid);
  EXPECT_EQ(joined.loose_joints[0].right_frame_guid,
            joined.loose_frames.at(0).guid);

  // The lock selected, the move handle drags both parts it joins.
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  auto point = [&](const std::string& key, int* x, int* y) {
    std::istringstream in(ReadLayout(layout_)[key]);
    return static_cast<bool>(in >> *x >> *y);
  };
  ASSERT_TRUE(WaitUntil([&] { return point("handle move", &x0, &y0); }, 90))
      << "no move handle on the loose lock";
  ASSERT_TRUE(point("handle +0.3x", &x1, &y1));
  ASSERT_TRUE(DragOnScreen(layout_, x0, y0, x1, y1, "handle drag", "move"))
      << ReadLayout(layout_)["handle drag"];
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "4"))
      << ReadLayout(layout_)["message"];
  const Scenario moved = Save();
  const Eigen::Vector3d frame =
      moved.loose_frames.at(0).position - joined.loose_frames.at(0).position;
  const Eigen::Vector3d sm = moved.loose_sensor_modules.at(0).position -
                             joined.loose_sensor_modules.at(0).position;
  EXPECT_NEAR(frame.x(), 0.3, 0.01);
  EXPECT_NEAR(frame.y(), 0.0, 0.01);
  EXPECT_NEAR((frame - sm).norm(), 0.0, 1e-9);  // as one
  EXPECT_EQ(moved.robots, joined.robots);
  studio_->Stop();
}

}  // namespace
}  // namespace mrsim::testing

// The inspector of the real mrsim-studio under its own Xvfb, typed into
// and clicked with real events (xdotool), as a student would.
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

class StudioInspectorWindow : public ::testing::Test {
 protected:
  void Start(const std::string& scenario,
             const std::vector<std::string>& flags) {
    layout_ = dir_ + "/layout.txt";
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok()) << "Xvfb did not start, see " << dir_;
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);
    std::vector<std::string> argv = {BinaryPath("studio/mrsim-studio"),
                                     "--layout-dump", layout_};
    argv.insert(argv.end(), flags.begin(), flags.end());
    argv.push_back(scenario);
    studio_ = std::make_unique<ChildProcess>(argv, dir_ + "/studio.log");
    ASSERT_TRUE(WaitForLayout(layout_, "revision", "0")) << studio_->Output();
  }

  // Types `text` into the field recorded as `widget` and presses Return,
  // held until the design has taken it (revision `revision`): ImGui 1.86
  // misses a key pressed and released within one frame. A click selects
  // the field's text whole, so the typing replaces it.
  void TypeAndEnter(const std::string& widget, const std::string& text,
                    int revision) {
    int x = 0, y = 0;
    ASSERT_TRUE(WidgetCentre(layout_, widget, &x, &y)) << widget;
    ASSERT_TRUE(ClickWhenThere(layout_, x, y));
    ASSERT_TRUE(WaitForLayout(layout_, "active", widget))
        << ReadLayout(layout_)["active"];
    ASSERT_TRUE(Xdotool({"type", text}));
    ASSERT_TRUE(Xdotool({"keydown", "Return"}));
    const bool taken =
        WaitForLayout(layout_, "revision", std::to_string(revision));
    ASSERT_TRUE(Xdotool({"keyup", "Return"}));
    ASSERT_TRUE(taken) << ReadLayout(layout_)["message"];
    // The field lets go of the keyboard a frame or more after it commits;
    // until then the studio gives keys to the field, so a Ctrl+S sent at
    // once on a loaded machine went to the field and never saved.
    ASSERT_TRUE(
        WaitUntil([&] { return ReadLayout(layout_).count("active") == 0; }, 90))
        << ReadLayout(layout_)["active"];
  }

  std::string dir_;
  std::string layout_;
  std::unique_ptr<XvfbDisplay> xvfb_;
  std::unique_ptr<ChildProcess> studio_;
};

// The case study with a long flat crate beside it, its x axis along x;
// `index` is its place among the scene objects.
std::string CaseStudyWithCrate(const std::string& dir, int* index) {
  Scenario s = ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  SceneObject crate;
  crate.guid = "crate";
  crate.is_static = true;
  crate.size = Eigen::Vector3d(0.3, 0.05, 0.05);
  crate.position = Eigen::Vector3d(0, 0.6, 0.025);
  s.scene_objects.push_back(crate);
  *index = static_cast<int>(s.scene_objects.size()) - 1;
  const std::string file = dir + "/crate.xml";
  WriteScenarioFile(s, file);
  return file;
}

TEST_F(StudioInspectorWindow, NinetyTypedInYawTurnsTheObjectAboutUp) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  dir_ = TempDir("studio_inspector_yaw");
  int index = 0;
  const std::string file = CaseStudyWithCrate(dir_, &index);
  Start(file, {"--select", "crate"});
  ASSERT_TRUE(
      WaitForLayout(layout_, "selected", "object 0 " + std::to_string(index)));
  ASSERT_NO_FATAL_FAILURE(TypeAndEnter("field /quatRotation yaw", "90", 1));
  // Saved with the Design panel's button: this test is about the field.
  int x = 0, y = 0;
  ASSERT_TRUE(WidgetCentre(layout_, "Save", &x, &y));
  ASSERT_TRUE(ClickWhenThere(layout_, x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "dirty", "0"))
      << ReadLayout(layout_)["message"];
  const SceneObject crate = ReadScenarioFile(file).scene_objects.at(index);
  // Its length now lies along y: a quarter turn about the up axis.
  const Eigen::Vector3d along = crate.quat_rotation * Eigen::Vector3d::UnitX();
  EXPECT_TRUE(along.isApprox(Eigen::Vector3d::UnitY(), 1e-9))
      << along.transpose();
  studio_->Stop();
}

// A camera added from the inspector (on the face its picker offers) shows
// its fields, and its remove button takes it off again; the saved file has
// the head camera alone.
TEST_F(StudioInspectorWindow, AddCameraShowsItsFieldsAndRemoveTakesItOff) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  dir_ = TempDir("studio_inspector_camera");
  const std::string file = dir_ + "/camera_snake.xml";
  fs::copy_file(SourcePath("scenarios/camera_snake.xml"), file);
  Start(file, {"--select", "sensor_module 0"});
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "sensor_module 0 0"));
  int x = 0, y = 0;
  ASSERT_TRUE(WidgetCentre(layout_, "add camera", &x, &y));
  ASSERT_TRUE(ClickWhenThere(layout_, x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "1"))
      << ReadLayout(layout_)["message"];
  ASSERT_TRUE(WaitUntil(
      [&] {
        return ReadLayout(layout_).count("widget field cameras[1]/fovy") > 0;
      },
      90));
  ASSERT_TRUE(WidgetCentre(layout_, "remove camera 1", &x, &y));
  ASSERT_TRUE(ClickWhenThere(layout_, x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "2"))
      << ReadLayout(layout_)["message"];
  ASSERT_TRUE(WidgetCentre(layout_, "Save", &x, &y));
  ASSERT_TRUE(ClickWhenThere(layout_, x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "dirty", "0"))
      << ReadLayout(layout_)["message"];
  const Scenario saved = ReadScenarioFile(file);
  const Scenario original =
      ReadScenarioFile(SourcePath("scenarios/camera_snake.xml"));
  EXPECT_EQ(saved.robots.at(0).sensor_modules.at(0).cameras,
            original.robots.at(0).sensor_modules.at(0).cameras);
  studio_->Stop();
}

}  // namespace
}  // namespace mrsim::testing

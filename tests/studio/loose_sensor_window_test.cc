// A loose sensor module in the real mrsim-studio under its own Xvfb,
// clicked with real events (xdotool): added beside the robot, given a
// camera and a distance sensor from its inspector, and saved with both on
// the loose module.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

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

class StudioLooseSensorWindow : public ::testing::Test {
 protected:
  void Start(const std::string& name) {
    dir_ = TempDir(name);
    file_ = dir_ + "/design.xml";
    fs::copy_file(SourcePath("scenarios/case_study.xml"), file_);
    layout_ = dir_ + "/layout.txt";
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok()) << "Xvfb did not start, see " << dir_;
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);
    studio_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{BinaryPath("studio/mrsim-studio"),
                                 "--layout-dump", layout_, file_},
        dir_ + "/studio.log");
    ASSERT_TRUE(WaitForLayout(layout_, "revision", "0")) << studio_->Output();
  }

  void ClickAndWait(const std::string& widget, int revision) {
    int x = 0, y = 0;
    ASSERT_TRUE(
        WaitUntil([&] { return WidgetCentre(layout_, widget, &x, &y); }, 90))
        << widget << " never shown";
    ASSERT_TRUE(ClickWhenThere(layout_, x, y)) << widget;
    ASSERT_TRUE(WaitForLayout(layout_, "revision", std::to_string(revision)))
        << widget << ": " << ReadLayout(layout_)["message"];
  }

  std::string dir_, file_, layout_;
  std::unique_ptr<XvfbDisplay> xvfb_;
  std::unique_ptr<ChildProcess> studio_;
};

TEST_F(StudioLooseSensorWindow, ALooseSensorModuleTakesACameraAndARay) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(Start("studio_loose_sensor_window"));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("Add loose part...", 0));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("loose sensor module", 1));
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "loose_sensor_module 0 0"));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("add camera", 2));
  ASSERT_NO_FATAL_FAILURE(ClickAndWait("add distance sensor", 3));
  // The camera's fields are offered as a robot's camera's are.
  ASSERT_TRUE(WaitUntil(
      [&] {
        return ReadLayout(layout_).count("widget field cameras[0]/fovy") > 0;
      },
      90));
  int x = 0, y = 0;
  ASSERT_TRUE(WidgetCentre(layout_, "Save", &x, &y));
  ASSERT_TRUE(ClickWhenThere(layout_, x, y));
  ASSERT_TRUE(WaitForLayout(layout_, "dirty", "0"))
      << ReadLayout(layout_)["message"];
  const Scenario saved = ReadScenarioFile(file_);
  ASSERT_EQ(saved.loose_sensor_modules.size(), 1u);
  const SensorModule& loose = saved.loose_sensor_modules[0];
  ASSERT_EQ(loose.cameras.size(), 1u);
  EXPECT_EQ(loose.cameras[0].sensor_position, 4) << "front first";
  ASSERT_EQ(loose.distance_sensors.size(), 1u);
  EXPECT_EQ(loose.distance_sensors[0].sensor_position, 4) << "front first";
  // The robot's sensor modules are as they were.
  const Scenario original =
      ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  ASSERT_EQ(saved.robots.at(0).sensor_modules.size(),
            original.robots.at(0).sensor_modules.size());
  for (size_t k = 0; k < saved.robots[0].sensor_modules.size(); ++k) {
    EXPECT_EQ(saved.robots[0].sensor_modules[k].cameras,
              original.robots[0].sensor_modules[k].cameras);
    EXPECT_EQ(saved.robots[0].sensor_modules[k].distance_sensors.size(),
              original.robots[0].sensor_modules[k].distance_sensors.size());
  }
  studio_->Stop();
}

}  // namespace
}  // namespace mrsim::testing

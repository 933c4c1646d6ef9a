// A loose sensor module takes distance sensors and cameras in the studio's
// editing model, as a robot's does: on the faces still free, saved on the
// loose module, removed again (REQ-1.3.4).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/design/design.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

Design SnakeAndALooseSensorModule() {
  Design d;
  d.AddPart(NextPart::kPitchModule);
  d.AddPart(NextPart::kYawModule);
  d.AddLoose(LoosePart::kSensorModule);
  return d;
}

TEST(StudioLooseSensor, ALooseSensorModuleTakesARayAndACameraOnFreeFaces) {
  Design d = SnakeAndALooseSensorModule();
  const Selection loose{SelectionKind::kLooseSensorModule, 0, 0};
  ASSERT_EQ(d.selection(), loose);
  // Alone beside the robot, every face looks out.
  EXPECT_EQ(d.OpenRayFaces(), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(d.OpenCameraFaces(), (std::vector<int>{0, 1, 2, 3, 4, 5}));

  d.AddDistanceSensor(4);
  d.AddCamera(4);
  const SensorModule& sm = d.scenario().loose_sensor_modules.at(0);
  ASSERT_EQ(sm.distance_sensors.size(), 1u);
  EXPECT_EQ(sm.distance_sensors[0].sensor_position, 4);
  ASSERT_EQ(sm.cameras.size(), 1u);
  EXPECT_EQ(sm.cameras[0].sensor_position, 4);
  // The robot's sensor modules are untouched.
  for (const Robot& r : d.scenario().robots) {
    for (const SensorModule& s : r.sensor_modules) {
      EXPECT_TRUE(s.distance_sensors.empty());
      EXPECT_TRUE(s.cameras.empty());
    }
  }
  // A taken face is no longer offered, and adding there is refused.
  const std::vector<int> rays = d.OpenRayFaces();
  EXPECT_EQ(std::count(rays.begin(), rays.end(), 4), 0);
  const std::vector<int> cameras = d.OpenCameraFaces();
  EXPECT_EQ(std::count(cameras.begin(), cameras.end(), 4), 0);
  EXPECT_THROW(d.AddCamera(4), DesignError);
  EXPECT_NO_THROW(ValidateScenario(d.scenario()));

  // Saved and read back, both are on the loose module.
  const std::string path =
      mrsim::testing::TempDir("studio_loose_sensor") + "/loose.xml";
  d.SaveAs(path);
  const Scenario saved = ReadScenarioFile(path);
  ASSERT_EQ(saved.loose_sensor_modules.size(), 1u);
  EXPECT_EQ(saved.loose_sensor_modules[0].distance_sensors.size(), 1u);
  EXPECT_EQ(saved.loose_sensor_modules[0].cameras.size(), 1u);

  d.RemoveCamera(0);
  d.RemoveDistanceSensor(0);
  EXPECT_TRUE(d.scenario().loose_sensor_modules[0].cameras.empty());
  EXPECT_TRUE(d.scenario().loose_sensor_modules[0].distance_sensors.empty());
}

// A force plate lays a robot's chain out on its plates: a loose module has
// no chain, so it is refused, saying why, and nothing changes.
TEST(StudioLooseSensor, APlateOnALooseSensorModuleIsRefused) {
  Design d = SnakeAndALooseSensorModule();
  const Scenario before = d.scenario();
  try {
    d.SetForcePlate(true);
    FAIL() << "a plate was put on a loose sensor module";
  } catch (const DesignError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("loose"));
  }
  EXPECT_EQ(d.scenario().loose_sensor_modules[0].force_sensor.has_value(),
            before.loose_sensor_modules[0].force_sensor.has_value());
}

}  // namespace
}  // namespace mrsim::studio

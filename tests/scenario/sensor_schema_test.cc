// A sensor module's IMU in scenario files, and equality of scenario parts
// as the schema lists their fields.
#include <gtest/gtest.h>

#include <variant>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/scenario/scenario_schema.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {
namespace {

Scenario ChainWithImu() {
  ChainOptions options;
  options.modules = 2;
  options.sensor_after = {-1};
  Scenario s;
  s.robots.push_back(MakeChain(options));
  Imu imu;
  imu.guid = "imu0";
  imu.accel_noise = 0.05;
  imu.gyro_noise = 0.002;
  imu.accel_bias = Eigen::Vector3d(0.1, -0.2, 0.3);
  imu.gyro_bias = Eigen::Vector3d(0.01, 0.02, -0.03);
  imu.seed = 42;
  s.robots[0].sensor_modules.at(0).imu = imu;
  return s;
}

TEST(ScenarioImu, RoundTripsThroughXmlWithEveryField) {
  const Scenario s = ChainWithImu();
  const std::string xml = WriteScenarioString(s);
  EXPECT_NE(xml.find("<imu>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<accelNoise>0.05</accelNoise>"), std::string::npos);
  EXPECT_NE(xml.find("<seed>42</seed>"), std::string::npos);
  const Scenario back = ReadScenarioString(xml, "imu.xml", "");
  ASSERT_TRUE(back.robots[0].sensor_modules[0].imu.has_value());
  EXPECT_EQ(back, s);
}

TEST(ScenarioImu, SensorModuleWithoutImuWritesNoImuElement) {
  Scenario s = ChainWithImu();
  s.robots[0].sensor_modules[0].imu.reset();
  EXPECT_EQ(WriteScenarioString(s).find("<imu>"), std::string::npos);
}

TEST(ScenarioImu, NegativeNoiseIsRefusedNamingTheField) {
  Scenario s = ChainWithImu();
  s.robots[0].sensor_modules[0].imu->gyro_noise = -1;
  try {
    ValidateScenario(s);
    FAIL() << "a negative noise validated";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("imu/gyroNoise"), std::string::npos)
        << e.what();
  }
}

TEST(ScenarioCamera, RoundTripsThroughXmlWithEveryField) {
  Scenario s = ChainWithImu();
  Camera c;
  c.guid = "eye";
  c.sensor_position = 2;
  c.fovy = 75;
  c.width = 320;
  c.height = 200;
  c.rate = 15;
  c.near_clip = 0.02;
  c.far_clip = 4;
  c.tilt = -12.5;
  c.noise = 3;
  c.seed = 9;
  s.robots[0].sensor_modules[0].cameras = {c, Camera{}};
  const std::string xml = WriteScenarioString(s);
  EXPECT_NE(xml.find("<cameras>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<tilt>-12.5</tilt>"), std::string::npos) << xml;
  const Scenario back = ReadScenarioString(xml, "camera.xml", "");
  ASSERT_EQ(back.robots[0].sensor_modules[0].cameras.size(), 2u);
  EXPECT_EQ(back, s);
  // A design without cameras keeps its files as they were.
  s.robots[0].sensor_modules[0].cameras.clear();
  EXPECT_EQ(WriteScenarioString(s).find("<cameras"), std::string::npos);
}

TEST(ScenarioCamera, ACameraIsAMujocoCameraLookingOutOfItsFace) {
  Scenario s = ChainWithImu();
  s.robots[0].sensor_modules[0].cameras.emplace_back().fovy = 50;
  const std::string mjcf = BuildMjcf(s);
  EXPECT_NE(mjcf.find("<camera name=\"snake/sm0/camera\""), std::string::npos)
      << mjcf;
  EXPECT_NE(mjcf.find("fovy=\"50\""), std::string::npos);
}

// Changes a field to another valid-looking value of its type.
void Change(const FieldRef& field) {
  std::visit(
      [&field](auto* v) {
        using T = std::remove_pointer_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::string>) {
          *v += "x";
        } else if constexpr (std::is_same_v<T, double> ||
                             std::is_same_v<T, int>) {
          *v += 1;
        } else if constexpr (std::is_same_v<T, bool>) {
          *v = !*v;
        } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
          *v += Eigen::Vector3d(1, 1, 1);
        } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
          v->w() += 1;
        } else {
          const std::vector<std::string> choices = field.choices();
          field.SetTextUnchecked(
              field.GetText() == choices.at(0) ? choices.at(1) : choices.at(0));
        }
      },
      field.value());
}

template <typename P>
void ExpectEveryFieldCounts(const P& part) {
  P copy = part;
  const size_t n = FieldsOf(copy).size();
  ASSERT_GT(n, 0u);
  for (size_t i = 0; i < n; ++i) {
    P changed = part;
    const FieldRef field = FieldsOf(changed)[i];
    Change(field);
    EXPECT_NE(changed, part) << field.info().xml;
    EXPECT_EQ(P(part), part);
  }
}

TEST(ScenarioEquality, EveryFieldTheSchemaListsCounts) {
  const Scenario s = ChainWithImu();
  const Robot& robot = s.robots[0];
  ExpectEveryFieldCounts(robot);
  ExpectEveryFieldCounts(robot.modules[0]);
  ExpectEveryFieldCounts(robot.modules[0].frames[0]);
  ExpectEveryFieldCounts(robot.modules[0].joint);
  ExpectEveryFieldCounts(robot.sensor_modules[0]);
  ExpectEveryFieldCounts(*robot.sensor_modules[0].imu);
  ExpectEveryFieldCounts(Camera{});
  ExpectEveryFieldCounts(ForceSensor{});
  ExpectEveryFieldCounts(DistanceSensor{});
  ExpectEveryFieldCounts(Scene{});
  ExpectEveryFieldCounts(SceneObject{});
  ExpectEveryFieldCounts(ContactFriction{});
  ExpectEveryFieldCounts(FluidRegion{});
  ExpectEveryFieldCounts(SimulationSettings{});
}

TEST(ScenarioEquality, ChildPartsCountAndWhereAFileCameFromDoesNot) {
  const Scenario s = ChainWithImu();
  Scenario other = s;
  other.base_dir = "/elsewhere";
  EXPECT_EQ(other, s);
  other.robots[0].sensor_modules[0].imu->seed = 1;
  EXPECT_NE(other, s);
  other = s;
  other.robots[0].sensor_modules[0].imu.reset();
  EXPECT_NE(other, s);
  other = s;
  other.robots[0].modules.pop_back();
  EXPECT_NE(other, s);
}

}  // namespace
}  // namespace mrsim

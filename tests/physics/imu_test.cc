// The IMU of a sensor module against physics: gravity at rest, the rate of
// a spin, and seeded noise and bias.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/sensor_kind.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

constexpr double kG = 9.81;

// One sensor module carrying `imu` at `position`, on flat ground.
Scenario ImuScenario(
    const Imu& imu, const Eigen::Vector3d& position,
    const Eigen::Quaterniond& rotation = Eigen::Quaterniond::Identity()) {
  Scenario s = testing::FlatScenario();
  Robot robot = testing::SensorModuleRobot("probe", position);
  robot.sensor_modules[0].quat_rotation = rotation;
  robot.sensor_modules[0].imu = imu;
  s.robots.push_back(robot);
  return s;
}

// A copy: a RobotState is often a temporary.
SensorReading ImuReading(const RobotState& state) {
  const std::vector<SensorReading>& r = state.sensor_modules.at(0).readings;
  if (r.size() != 1u) {
    ADD_FAILURE() << "readings: " << r.size();
    return {};
  }
  EXPECT_EQ(r.at(0).kind, "imu");
  EXPECT_EQ(r.at(0).values.size(), 6u);
  return r.at(0);
}

Eigen::Vector3d Accel(const SensorReading& r) {
  return {r.values[0], r.values[1], r.values[2]};
}
Eigen::Vector3d Gyro(const SensorReading& r) {
  return {r.values[3], r.values[4], r.values[5]};
}

TEST(PhysicsImu, ModuleAtRestReadsGravityUpAndNoRate) {
  Physics physics(ImuScenario(Imu{}, Eigen::Vector3d(0, 0, 0.03)));
  physics.Step(500);  // settled on the ground
  const RobotState state = physics.ReadRobotState(0);
  const SensorReading r = ImuReading(state);
  EXPECT_NEAR(Accel(r).x(), 0, 0.05);
  EXPECT_NEAR(Accel(r).y(), 0, 0.05);
  EXPECT_NEAR(Accel(r).z(), kG, 0.05);  // accelerometer convention: +g up
  EXPECT_LT(Gyro(r).norm(), 1e-3);
}

TEST(PhysicsImu, ReadingsAreInTheModulesOwnFrame) {
  // Turned 90 degrees about x: the module's y axis points up.
  const Eigen::Quaterniond turned(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  Physics physics(ImuScenario(Imu{}, Eigen::Vector3d(0, 0, 0.03), turned));
  physics.Step(500);
  const RobotState state = physics.ReadRobotState(0);
  const Eigen::Vector3d expected =
      state.sensor_modules[0].pose.orientation.inverse() *
      Eigen::Vector3d(0, 0, kG);
  EXPECT_NEAR(expected.y(), kG, 0.1);
  EXPECT_LT((Accel(ImuReading(state)) - expected).norm(), 0.05);
}

TEST(PhysicsImu, SpinningModuleReadsItsRate) {
  Scenario s = ImuScenario(Imu{}, Eigen::Vector3d(0, 0, 0.5));
  s.settings.gravity.setZero();  // floats, spinning freely
  Physics physics(s);
  // The free joint's angular velocity is in the body's frame.
  mjData* d = physics.mutable_data();
  d->qvel[3] = 0.0;
  d->qvel[4] = 0.0;
  d->qvel[5] = 2.0;  // rad/s about the module's z axis
  physics.Step(100);
  const SensorReading r = ImuReading(physics.ReadRobotState(0));
  EXPECT_NEAR(Gyro(r).z(), 2.0, 1e-3);
  EXPECT_NEAR(Gyro(r).x(), 0.0, 1e-3);
  EXPECT_NEAR(Gyro(r).y(), 0.0, 1e-3);
  EXPECT_LT(Accel(r).norm(), 0.05);  // at the centre of the spin, in free fall
}

TEST(PhysicsImu, BiasAddsAndNoiseIsTheSameForTheSameSeed) {
  Imu imu;
  imu.accel_bias = Eigen::Vector3d(0.5, 0, 0);
  imu.gyro_bias = Eigen::Vector3d(0, 0, 0.1);
  imu.accel_noise = 0.2;
  imu.gyro_noise = 0.01;
  imu.seed = 7;
  auto run = [](const Imu& imu) {
    Physics physics(ImuScenario(imu, Eigen::Vector3d(0, 0, 0.03)));
    physics.Step(300);
    std::vector<double> values;
    for (int i = 0; i < 200; ++i) {
      physics.Step(1);
      const SensorReading r = ImuReading(physics.ReadRobotState(0));
      values.insert(values.end(), r.values.begin(), r.values.end());
    }
    return values;
  };
  const std::vector<double> a = run(imu);
  EXPECT_EQ(a, run(imu));
  Imu other = imu;
  other.seed = 8;
  EXPECT_NE(a, run(other));

  // Mean = gravity + bias, spread = the noise's standard deviation.
  double mean_x = 0, mean_z = 0, mean_gz = 0, var_x = 0;
  const int n = static_cast<int>(a.size() / 6);
  for (int i = 0; i < n; ++i) {
    mean_x += a[6 * i] / n;
    mean_z += a[6 * i + 2] / n;
    mean_gz += a[6 * i + 5] / n;
  }
  for (int i = 0; i < n; ++i) {
    var_x += (a[6 * i] - mean_x) * (a[6 * i] - mean_x) / (n - 1);
  }
  EXPECT_NEAR(mean_x, 0.5, 0.06);
  EXPECT_NEAR(mean_z, kG, 0.06);
  EXPECT_NEAR(mean_gz, 0.1, 0.003);
  EXPECT_NEAR(std::sqrt(var_x), 0.2, 0.04);
}

TEST(PhysicsImu, ModelHasMujocosAccelerometerAndGyroOnTheModulesCentre) {
  const std::string mjcf =
      BuildMjcf(ImuScenario(Imu{}, Eigen::Vector3d(0, 0, 0.03)));
  EXPECT_NE(mjcf.find("<site name=\"probe/sm0/imu\" pos=\"0 0 0\""),
            std::string::npos)
      << mjcf;
  EXPECT_NE(mjcf.find("<accelerometer name=\"probe/sm0/imu/accel\" "
                      "site=\"probe/sm0/imu\"/>"),
            std::string::npos);
  EXPECT_NE(
      mjcf.find("<gyro name=\"probe/sm0/imu/gyro\" site=\"probe/sm0/imu\"/>"),
      std::string::npos);
}

TEST(PhysicsImu, IsDrawnAsAChipWithTheModulesAxesOnItsTopFace) {
  // Sites only: what the viewer and the studio show, nothing that weighs
  // or collides. The chip sits on the top face (the IMU itself is inside).
  const Scenario s = ImuScenario(Imu{}, Eigen::Vector3d(0, 0, 0.03));
  const std::string mjcf = BuildMjcf(s);
  const double top = s.robots[0].sensor_modules[0].size.z() / 2;
  for (const char* part : {"look", "x", "y", "z"}) {
    const std::string name = std::string("probe/sm0/imu/") + part;
    const size_t at = mjcf.find("<site name=\"" + name + "\"");
    ASSERT_NE(at, std::string::npos) << name << "\n" << mjcf;
    const std::string element = mjcf.substr(at, mjcf.find('>', at) - at);
    EXPECT_NE(element.find("rgba=\""), std::string::npos) << element;
    EXPECT_EQ(element.find("group="), std::string::npos) << element;  // shown
    double x = 0, y = 0, z = 0;
    const size_t pos = element.find("pos=\"");
    ASSERT_NE(pos, std::string::npos) << element;
    ASSERT_EQ(
        std::sscanf(element.c_str() + pos, "pos=\"%lf %lf %lf", &x, &y, &z), 3)
        << element;
    EXPECT_GT(z, top) << element;
  }
  EXPECT_NE(mjcf.find("name=\"probe/sm0/imu/look\" pos=\"0 0"),
            std::string::npos);
  // The marker changes no reading: the same as a model without it would
  // give is checked by ModuleAtRestReadsGravityUpAndNoRate; here, no geom.
  EXPECT_EQ(mjcf.find("<geom name=\"probe/sm0/imu"), std::string::npos);
}

TEST(PhysicsImu, ModuleWithoutImuHasNoReadings) {
  Scenario s = ImuScenario(Imu{}, Eigen::Vector3d(0, 0, 0.03));
  s.robots[0].sensor_modules[0].imu.reset();
  Physics physics(s);
  physics.Step(10);
  EXPECT_TRUE(physics.ReadRobotState(0).sensor_modules[0].readings.empty());
}

TEST(SensorKinds, EveryKindHasWhatTheBuilderPhysicsAndStudioNeed) {
  for (const SensorKind& kind : SensorKinds()) {
    EXPECT_EQ(FindSensorKind(kind.name), &kind);
    EXPECT_NE(kind.count, nullptr) << kind.name;
    EXPECT_NE(kind.face, nullptr) << kind.name;
    // Every kind but the camera is read by the physics the same way; a
    // camera's pictures are rendered outside it.
    const bool camera = kind.mount == SensorMount::kCamera;
    EXPECT_EQ(kind.channels.empty(), camera) << kind.name;
    EXPECT_EQ(kind.read == nullptr, camera) << kind.name;
    EXPECT_EQ(camera, kind.camera != nullptr) << kind.name;
    EXPECT_EQ(kind.mount == SensorMount::kPlate, kind.plate != nullptr)
        << kind.name;
    EXPECT_EQ(kind.mount == SensorMount::kRay, kind.ray != nullptr)
        << kind.name;
    // A centre kind has nothing but MuJoCo's sensors to read.
    if (kind.mount == SensorMount::kCentre) {
      EXPECT_FALSE(kind.mujoco.empty()) << kind.name;
    }
    // The studio's inspector shows every kind.
    EXPECT_NE(kind.fields, nullptr) << kind.name;
    EXPECT_NE(std::string(kind.member), "") << kind.name;
  }
  // The four kinds a sensor module carries, by their mounts.
  EXPECT_EQ(FindSensorKind("force")->mount, SensorMount::kPlate);
  EXPECT_EQ(FindSensorKind("distance")->mount, SensorMount::kRay);
  EXPECT_EQ(FindSensorKind("imu")->mount, SensorMount::kCentre);
  EXPECT_EQ(FindSensorKind("camera")->mount, SensorMount::kCamera);
  EXPECT_EQ(FindSensorKind("sonar"), nullptr);
}

}  // namespace
}  // namespace mrsim

// Force and distance sensors against values computed from the scene.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"
#include "tests/common/child_process.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

DistanceSensor Ray(int face, const Eigen::Vector3d& direction, double range) {
  DistanceSensor ds;
  ds.guid = "ray" + std::to_string(face);
  ds.sensor_position = face;
  ds.ray_direction = direction;
  ds.max_ray_distance = range;
  ds.mass = 0.001;
  ds.size = Eigen::Vector3d(0.01, 0.01, 0.01);
  return ds;
}

SceneObject StaticBox(const Eigen::Vector3d& position,
                      const Eigen::Vector3d& size) {
  SceneObject box;
  box.guid = "box";
  box.position = position;
  box.size = size;
  box.is_static = true;
  return box;
}

TEST(PhysicsDistanceSensor, ReadsBoxTerrainAndMaxRange) {
  Scenario s = testing::FlatScenario();
  s.settings.gravity.setZero();  // the module floats where it is put
  Robot robot = testing::SensorModuleRobot("probe", Eigen::Vector3d(0, 0, 0.3));
  SensorModule& sm = robot.sensor_modules[0];
  sm.distance_sensors.push_back(
      Ray(4, Eigen::Vector3d::UnitX(), 2.0));  // front
  sm.distance_sensors.push_back(
      Ray(0, -Eigen::Vector3d::UnitZ(), 2.0));                           // down
  sm.distance_sensors.push_back(Ray(2, Eigen::Vector3d::UnitZ(), 1.5));  // up
  // Looks back through its own module: must see the box behind, not itself.
  sm.distance_sensors.push_back(Ray(4, -Eigen::Vector3d::UnitX(), 2.0));
  s.robots.push_back(robot);
  s.scene_objects.push_back(
      StaticBox(Eigen::Vector3d(0.8, 0, 0.3), Eigen::Vector3d(0.2, 0.4, 0.4)));
  s.scene_objects.push_back(
      StaticBox(Eigen::Vector3d(-0.6, 0, 0.3), Eigen::Vector3d(0.2, 0.4, 0.4)));
  s.scene_objects.back().guid = "box behind";  // guids are unique
  Physics physics(s);
  physics.Step();
  const SensorModuleState state = physics.ReadRobotState(0).sensor_modules[0];
  ASSERT_EQ(state.distances.size(), 4u);
  EXPECT_EQ(state.distance_faces, (std::vector<int>{4, 0, 2, 4}));
  // Front face at x = 0.025, box face at x = 0.7.
  EXPECT_NEAR(state.distances[0], 0.675, 1e-6);
  // Bottom face at z = 0.275, ground plane at 0.
  EXPECT_NEAR(state.distances[1], 0.275, 1e-6);
  // Nothing above within range.
  EXPECT_DOUBLE_EQ(state.distances[2], 1.5);
  // From the front face backwards: the far box face at x = -0.5.
  EXPECT_NEAR(state.distances[3], 0.525, 1e-6);
}

TEST(PhysicsDistanceSensor, SeesTerrainHeightAndOtherRobots) {
  const std::string dir = testing::TempDir("physics_ray_terrain");
  testing::WriteGreyPng(dir + "/step.png", 10, 10,
                        [](int, int c) { return c < 5 ? 0 : 255; });
  Scenario s = testing::FlatScenario();
  s.settings.gravity.setZero();
  s.base_dir = dir;
  s.scene.height_image = "step.png";
  s.scene.height = 0.2;
  s.scene.meters_per_pixel = 0.1;  // 1 m x 1 m from (0, 0)
  // Above the high half (x in [0.5, 1]): bottom face at 0.475.
  Robot robot =
      testing::SensorModuleRobot("probe", Eigen::Vector3d(0.8, 0.5, 0.5));
  robot.sensor_modules[0].distance_sensors.push_back(
      Ray(0, -Eigen::Vector3d::UnitZ(), 2.0));
  robot.sensor_modules[0].distance_sensors.push_back(
      Ray(5, -Eigen::Vector3d::UnitX(), 2.0));
  s.robots.push_back(robot);
  // Another robot behind it, its near face at x = 0.4 - 0.025.
  s.robots.push_back(
      testing::SensorModuleRobot("other", Eigen::Vector3d(0.4, 0.5, 0.5)));
  Physics physics(s);
  physics.Step();
  const SensorModuleState state = physics.ReadRobotState(0).sensor_modules[0];
  EXPECT_NEAR(state.distances[0], 0.475 - 0.2, 1e-6);
  EXPECT_NEAR(state.distances[1], (0.8 - 0.025) - (0.4 + 0.025), 1e-6);
}

TEST(PhysicsDistanceSensor, SkipsItsOwnForcePlate) {
  Scenario s = testing::FlatScenario();
  Robot robot = testing::SensorModuleRobot("probe", Eigen::Vector3d(0, 0, 0.2));
  SensorModule& sm = robot.sensor_modules[0];
  sm.force_sensor = ForceSensor();
  sm.distance_sensors.push_back(Ray(0, -Eigen::Vector3d::UnitZ(), 1.0));
  s.robots.push_back(robot);
  Physics physics(s);
  physics.Step(500);  // falls and rests on its plate
  const SensorModuleState state = physics.ReadRobotState(0).sensor_modules[0];
  // Bottom face to ground = the plate's thickness, not 0.
  EXPECT_NEAR(state.distances[0], sm.force_sensor->size.z(), 2e-4);
}

TEST(PhysicsForceSensor, PlateUnderRestingModuleCarriesItsWeight) {
  Scenario s = testing::FlatScenario();
  Robot robot =
      testing::SensorModuleRobot("scale", Eigen::Vector3d(0, 0, 0.03), 0.12);
  SensorModule& sm = robot.sensor_modules[0];
  sm.force_sensor = ForceSensor();
  sm.distance_sensors.push_back(Ray(4, Eigen::Vector3d::UnitX(), 1.0));
  s.robots.push_back(robot);
  Physics physics(s);
  physics.Step(1000);
  const SensorModuleState state = physics.ReadRobotState(0).sensor_modules[0];
  ASSERT_TRUE(state.has_force);
  // The plate carries everything above it: module plus distance sensor.
  const double carried = (sm.mass + sm.distance_sensors[0].mass) * 9.81;
  EXPECT_NEAR(state.force, carried, 0.01 * carried);
}

TEST(PhysicsForceSensor, ChainPlatesShareTheRobotsWeight) {
  // Sensor modules with plates under them at both ends and the middle of a
  // chain: the chain's frames hover a plate's thickness above the ground,
  // so the plates carry the whole robot.
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 2;
  options.sensor_after = {-1, 0, 1};
  options.force_sensors = true;
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  physics.Step(1000);
  const RobotState state = physics.ReadRobotState(0);
  double plates = 0, total = 0;
  for (const SensorModuleState& sm : state.sensor_modules) plates += sm.force;
  const mjModel* m = physics.model();
  for (int b = 1; b < m->nbody; ++b) total += m->body_mass[b];
  double plate_mass = 0;
  for (const SensorModule& sm : s.robots[0].sensor_modules) {
    plate_mass += sm.force_sensor->mass;
  }
  const double expected = (total - plate_mass) * 9.81;
  EXPECT_NEAR(plates, expected, 0.03 * expected);
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

TEST(PhysicsTerrain, ImageTopRowIsThePlusYEdge) {
  const std::string dir = testing::TempDir("physics_terrain_rows");
  // Top half of the image bright: the +y half of the terrain is high.
  testing::WriteGreyPng(dir + "/rows.png", 10, 10,
                        [](int r, int) { return r < 5 ? 255 : 0; });
  Scenario s = testing::FlatScenario();
  s.settings.gravity.setZero();
  s.base_dir = dir;
  s.scene.height_image = "rows.png";
  s.scene.height = 0.2;
  s.scene.meters_per_pixel = 0.1;
  for (double y : {0.8, 0.2}) {
    Robot probe = testing::SensorModuleRobot(
        "probe" + std::to_string(static_cast<int>(y * 10)),
        Eigen::Vector3d(0.5, y, 0.5));
    DistanceSensor down;
    down.sensor_position = 0;
    down.ray_direction = -Eigen::Vector3d::UnitZ();
    probe.sensor_modules[0].distance_sensors.push_back(down);
    s.robots.push_back(probe);
  }
  Physics physics(s);
  EXPECT_NEAR(physics.ReadRobotState(0).sensor_modules[0].distances[0],
              0.475 - 0.2, 1e-6);
  EXPECT_NEAR(physics.ReadRobotState(1).sensor_modules[0].distances[0], 0.475,
              1e-6);
}

}  // namespace
}  // namespace mrsim

// Turns a Scenario into MuJoCo MJCF text. The output is self-contained apart
// from mesh and height-field files, which it names by absolute path, so it
// opens in mujoco-simulate / mujoco-testxml. Names of bodies, joints,
// actuators, sites and sensors follow MjcfNames below (docs/physics.md).
#pragma once

#include <Eigen/Core>
#include <string>

#include "sim_core/scenario.h"

namespace mrsim {

// Servo model shared by the builder and the physics: a MuJoCo velocity
// actuator (force = kv * (ctrl - qvel), clamped to +-force_limit) on a hinge
// with the reflected rotor inertia of a geared servo (armature).
struct ServoModel {
  static constexpr double kKv = 5.0;          // N m s / rad
  static constexpr double kForceLimit = 2.0;  // N m (stall torque)
  static constexpr double kArmature = 0.01;   // kg m^2
};

struct MjcfOptions {
  // false (export): the height field names a grey PNG by absolute path (the
  // scene's own PNG file, or the decoded image written to asset_dir, or to
  // the system temp directory when asset_dir is empty).
  // true (what Physics uses): the height field only declares nrow/ncol and
  // the caller fills mjModel::hfield_data with HeightFieldData().
  bool hfield_data_after_compile = false;
  std::string asset_dir;
};

// Export form: equal to BuildMjcf(scenario, MjcfOptions{}).
std::string BuildMjcf(const Scenario& scenario);
// Throws ScenarioError (ValidateScenario, naming the element path) on
// anything the simulator cannot run, std::runtime_error when a mesh file
// vanished or the terrain image cannot be written.
std::string BuildMjcf(const Scenario& scenario, const MjcfOptions& options);

// Outward normal of a sensor module face in the module's own frame (the
// chain runs along +x, z up): 0 bottom -z, 1 left +y, 2 top +z, 3 right -y,
// 4 front +x, 5 back -x. Force plates use 0..3, distance sensors 0..5.
// Throws std::out_of_range for anything else.
Eigen::Vector3d SensorFaceNormal(int sensor_position);

// The MJCF names of every part. `robot` is Robot::name (or "robot<i>" when
// empty), indices are positions in the scenario's lists.
namespace mjcf_names {
std::string RobotName(const Scenario& scenario, int robot);
std::string RootJoint(const std::string& robot, int component);  // "r/root"
std::string FrameBody(const std::string& robot, int module, int frame);
std::string Hinge(const std::string& robot, int module);         // "r/m3/hinge"
std::string Servo(const std::string& robot, int module);         // "r/m3/servo"
std::string SensorModuleBody(const std::string& robot, int sm);  // "r/sm2"
std::string PlateBody(const std::string& robot, int sm);    // "r/sm2/plate"
std::string ForceSite(const std::string& robot, int sm);    // ".../plate_site"
std::string ForceSensor(const std::string& robot, int sm);  // "r/sm2/force"
std::string DistanceSite(const std::string& robot, int sm,
                         int k);     // "r/sm2/d0"
std::string SceneObject(int index);  // "scene/obj<i>"
std::string Terrain();               // "scene/terrain" (hfield or plane)
}  // namespace mjcf_names

}  // namespace mrsim

// Generates a plain chain robot so nobody hand-writes XML for a snake.
//
// Geometry (other components rely on it):
// - The chain lies along the x axis, module 0 at the front (largest x), so
//   "forward" is +x. Parts from front to back: [sensor module if -1 is in
//   sensor_after], module 0, [sensor module after 0], module 1, ...
// - Every module is two Box frames of frame_size, touching at the module
//   position, which is the hinge anchor. frames[0] ("<name>/m<i>/f0") is
//   the front frame (+x side), frames[1] ("<name>/m<i>/f1") the back one.
//   The hinge joint "<name>/m<i>/joint" has left = f0, right = f1; its axis
//   is y for Pitch (bends up/down) and z for Yaw (bends left/right).
// - Module 0's hinge is at (origin.x, origin.y); every part's centre is at
//   z = origin.z + frame_size.z / 2 (+ the force plate thickness when
//   force_sensors is set, so the chain stands on the plates), i.e. the
//   chain rests on a ground plane at height origin.z.
// - A sensor module "<name>/s<k>" (k counts from the front) is a box of
//   frame_size between two modules: left_mod_nr is the module in front of
//   it, right_mod_nr the one behind (-1 at a chain end).
// - Consecutive parts are locked by Lock joints "<name>/lock<k>" in
//   robot.locks (k from the front); left = the front part's touching frame
//   (a module's f1, or the sensor module guid), right = the back part's.
// - force_sensors: a plate "<name>/s<k>/force" of ForceSensor's default
//   size under the sensor module (sensorPosition 0), locked to it by
//   "<name>/s<k>/force_lock" at the centre of the bottom face.
// - front_distance_sensor: "<name>/s<k>/d0" on the front face
//   (sensorPosition 4 = +x, see docs/scenario.md) of the frontmost sensor
//   module, ray along +x, locked by "<name>/s<k>/d0_lock".
#pragma once

#include <string>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

enum class ChainPattern { kPitch, kYaw, kPitchYaw };

struct ChainOptions {
  std::string name = "snake";
  int modules = 11;
  ChainPattern pattern = ChainPattern::kPitch;  // kPitchYaw: module 0 Pitch
  double module_mass = 0.1;                     // kg, split over the two frames
  Eigen::Vector3d frame_size = Eigen::Vector3d(0.05, 0.05, 0.05);  // box
  double kp = 10.0;
  double max_vel = 3.0;
  double joint_limit = 1.5708;  // symmetric range limit, rad
  // Sensor module after module i for i in sensor_after (none by default);
  // -1 puts one in front of module 0.
  std::vector<int> sensor_after;
  bool force_sensors = false;          // one under each sensor module
  bool front_distance_sensor = false;  // on the frontmost sensor module
  std::string material = "plastic";
  // The ground point under module 0's hinge (see the geometry above).
  Eigen::Vector3d origin = Eigen::Vector3d(0, 0, 0);
};

// Builds the chain described above. Throws std::invalid_argument on
// modules < 1, non-positive sizes or masses, a sensor_after entry outside
// [-1, modules-1] or repeated, or front_distance_sensor without a sensor
// module in front of module 0. The caller places the robot in a Scenario.
Robot MakeChain(const ChainOptions& options);

// Where `--sensors none|all|between` puts sensor modules
// (ChainOptions::sensor_after) in a chain of `modules`: nowhere, in front
// of module 0 and after every module, or between consecutive modules.
enum class SensorPlacement { kNone, kAll, kBetween };
std::vector<int> SensorsAfter(SensorPlacement placement, int modules);

// What `mrsim-scenario new` makes (and the studio's "New robot from
// template"): one chain on flat ground of `ground_material`, with a
// robot-ground ContactFriction when friction >= 0.
struct ChainScenarioOptions {
  ChainOptions chain;
  std::string ground_material = "ground";
  double friction = -1;  // < 0: no ContactFriction
};
// Throws std::invalid_argument as MakeChain does.
Scenario MakeChainScenario(const ChainScenarioOptions& options);

// A Lock joint holding `right` rigidly to `left` (limits 0), as the chain's
// locks and sensor mounts are.
Joint MakeLock(const std::string& guid, const std::string& left,
               const std::string& right);

}  // namespace mrsim

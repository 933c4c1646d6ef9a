// Generates a plain chain robot so nobody hand-writes XML for a snake.
#pragma once

#include <string>

#include "sim_core/scenario.h"

namespace mrsim {

enum class ChainPattern { kPitch, kYaw, kPitchYaw };

struct ChainOptions {
  std::string name = "snake";
  int modules = 11;
  ChainPattern pattern = ChainPattern::kPitch;
  double module_mass = 0.1;          // kg, split over the two frames
  Eigen::Vector3d frame_size = Eigen::Vector3d(0.05, 0.05, 0.05);  // box
  double kp = 10.0;
  double max_vel = 3.0;
  double joint_limit = 1.5708;       // symmetric range limit, rad
  // Sensor module after module i for i in sensor_after (none by default);
  // -1 puts one in front of module 0.
  std::vector<int> sensor_after;
  bool force_sensors = false;        // one under each sensor module
  bool front_distance_sensor = false;  // on the frontmost sensor module
  std::string material = "plastic";
  Eigen::Vector3d origin = Eigen::Vector3d(0, 0, 0.03);  // first module
};

// The chain lies along +x, module 0 at the front (largest x). Robot added to
// nothing: the caller places it in a Scenario.
Robot MakeChain(const ChainOptions& options);

}  // namespace mrsim

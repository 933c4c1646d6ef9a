// Where things sit on a sensor module's faces, in the module's own frame:
// the one geometry the validator, the MJCF builder, the physics and the
// studio share (no MJCF in here).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Outward normal of a sensor module face in the module's own frame (the
// chain runs along +x, z up): 0 bottom -z, 1 left +y, 2 top +z, 3 right -y,
// 4 front +x, 5 back -x. Force plates use 0..3, distance sensors 0..5.
// Throws std::out_of_range for anything else.
Eigen::Vector3d SensorFaceNormal(int sensor_position);

// Where the physics puts a sensor module's force plate, in the module's
// own frame: flat on its face (sensorPosition), outside the module, its
// thickness (size.z) along the face normal. The plate's own position in
// the file is not used. Throws std::out_of_range as SensorFaceNormal.
struct PlatePose {
  Eigen::Vector3d position;
  Eigen::Quaterniond rotation;
};
PlatePose ForcePlatePose(const SensorModule& sm);

}  // namespace mrsim

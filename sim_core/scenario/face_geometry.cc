#include "sim_core/scenario/face_geometry.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mrsim {

using Eigen::Quaterniond;
using Eigen::Vector3d;

Vector3d SensorFaceNormal(int sensor_position) {
  switch (sensor_position) {
    case 0:
      return -Vector3d::UnitZ();
    case 1:
      return Vector3d::UnitY();
    case 2:
      return Vector3d::UnitZ();
    case 3:
      return -Vector3d::UnitY();
    case 4:
      return Vector3d::UnitX();
    case 5:
      return -Vector3d::UnitX();
    default:
      throw std::out_of_range("sensorPosition must be 0..5, got " +
                              std::to_string(sensor_position));
  }
}

PlatePose ForcePlatePose(const SensorModule& sm) {
  const ForceSensor& plate = *sm.force_sensor;
  const Vector3d n = SensorFaceNormal(plate.sensor_position);
  const double h = std::abs(n.dot(sm.size / 2));
  return {n * (h + plate.size.z() / 2),
          Quaterniond::FromTwoVectors(Vector3d::UnitZ(), n)};
}

}  // namespace mrsim

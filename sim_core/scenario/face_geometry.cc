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

CameraPose CameraOnFace(const Camera& camera, const Vector3d& size) {
  const Vector3d n = SensorFaceNormal(camera.sensor_position);
  CameraPose pose;
  pose.position = n * std::abs(n.dot(size / 2));
  const Vector3d up0 = std::abs(n.z()) > 0.5 ? Vector3d::UnitX().eval()
                                             : Vector3d::UnitZ().eval();
  const double t = camera.tilt * 3.14159265358979323846 / 180;
  const Vector3d forward = std::cos(t) * n - std::sin(t) * up0;
  const Vector3d up = std::sin(t) * n + std::cos(t) * up0;
  Eigen::Matrix3d axes;
  axes.col(0) = forward.cross(up);  // right
  axes.col(1) = up;
  axes.col(2) = -forward;
  pose.rotation = Quaterniond(axes).normalized();
  return pose;
}

Vector3d SceneObjectBox(const SceneObject& object) {
  const Vector3d& s = object.size;
  switch (object.shape) {
    case PrimitiveShape::kBox:
      return s;
    case PrimitiveShape::kSphere:
      return Vector3d(s.x(), s.x(), s.x());
    case PrimitiveShape::kCylinder:
    case PrimitiveShape::kCapsule:
      return Vector3d(s.x(), s.x(), s.z());
  }
  return s;
}

}  // namespace mrsim

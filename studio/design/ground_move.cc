#include "studio/design/ground_move.h"

#include <cmath>

namespace mrsim::studio {
namespace {

void Place(const Eigen::Isometry3d& t, Eigen::Vector3d* position) {
  *position = t * *position;
}

void Place(const Eigen::Isometry3d& t, Eigen::Vector3d* position,
           Eigen::Quaterniond* rotation) {
  *position = t * *position;
  *rotation = Eigen::Quaterniond(t.linear()) * *rotation;
  rotation->normalize();
}

}  // namespace

Eigen::Isometry3d GroundTransform(const Eigen::Vector3d& pivot,
                                  const GroundMove& move) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Eigen::Vector3d(move.shift.x(), move.shift.y(), 0) + pivot);
  t.rotate(Eigen::AngleAxisd(move.turn, Eigen::Vector3d::UnitZ()));
  t.translate(-pivot);
  return t;
}

Eigen::Vector3d RobotPivot(const Robot& robot) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (const Module& m : robot.modules) {
    sum += m.position;
    ++n;
  }
  for (const SensorModule& sm : robot.sensor_modules) {
    sum += sm.position;
    ++n;
  }
  return n == 0 ? sum : Eigen::Vector3d(sum / n);
}

double RobotHeading(const Robot& robot) {
  if (robot.modules.empty()) return 0.0;
  const Eigen::Vector3d x =
      robot.modules[0].frames[0].quat_rotation * Eigen::Vector3d::UnitX();
  if (std::hypot(x.x(), x.y()) < 1e-9) return 0.0;  // pointing straight up
  return std::atan2(x.y(), x.x());
}

void TransformRobot(Robot* robot, const Eigen::Isometry3d& t) {
  for (Module& m : robot->modules) {
    Place(t, &m.position);
    for (Frame& f : m.frames) Place(t, &f.position, &f.quat_rotation);
  }
  for (SensorModule& sm : robot->sensor_modules) {
    Place(t, &sm.position, &sm.quat_rotation);
    Place(t, &sm.force_lock_position);
    Place(t, &sm.distance_lock_position);
    if (sm.force_sensor) {
      Place(t, &sm.force_sensor->position, &sm.force_sensor->rotation);
    }
    // Ray directions are in the sensor module's frame: they turn with it.
    for (DistanceSensor& d : sm.distance_sensors) {
      Place(t, &d.position, &d.quat_rotation);
    }
  }
}

void MoveRobot(Robot* robot, const GroundMove& move) {
  if (move.empty()) return;
  TransformRobot(robot, GroundTransform(RobotPivot(*robot), move));
}

void MoveObject(SceneObject* object, const GroundMove& move) {
  if (move.empty()) return;
  Place(GroundTransform(object->position, move), &object->position,
        &object->quat_rotation);
  object->rotation.z() += move.turn * 180.0 / M_PI;
}

}  // namespace mrsim::studio

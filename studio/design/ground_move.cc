#include "studio/design/ground_move.h"

#include <cmath>
#include <map>
#include <string>

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
  for (SensorModule& sm : robot->sensor_modules) TransformSensorModule(&sm, t);
}

void TransformSensorModule(SensorModule* sm, const Eigen::Isometry3d& t) {
  Place(t, &sm->position, &sm->quat_rotation);
  Place(t, &sm->force_lock_position);
  Place(t, &sm->distance_lock_position);
  if (sm->force_sensor) {
    Place(t, &sm->force_sensor->position, &sm->force_sensor->rotation);
  }
  // Ray directions are in the sensor module's frame: they turn with it.
  for (DistanceSensor& d : sm->distance_sensors) {
    Place(t, &d.position, &d.quat_rotation);
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

std::vector<Selection> LooseGroup(const Scenario& s, const Selection& sel) {
  const int n = static_cast<int>(sel.index);
  std::vector<std::string> start;
  switch (sel.kind) {
    case SelectionKind::kLooseFrame:
      if (n < 0 || n >= static_cast<int>(s.loose_frames.size())) return {};
      start.push_back(s.loose_frames[n].guid);
      break;
    case SelectionKind::kLooseSensorModule:
      if (n < 0 || n >= static_cast<int>(s.loose_sensor_modules.size())) {
        return {};
      }
      start.push_back(s.loose_sensor_modules[n].guid);
      break;
    case SelectionKind::kLooseJoint:
      if (n < 0 || n >= static_cast<int>(s.loose_joints.size())) return {};
      start.push_back(s.loose_joints[n].left_frame_guid);
      start.push_back(s.loose_joints[n].right_frame_guid);
      break;
    default:
      return {};
  }
  // Every part reached from `start` through loose joints.
  std::map<std::string, bool> reached;
  std::vector<std::string> todo = start;
  while (!todo.empty()) {
    const std::string guid = todo.back();
    todo.pop_back();
    if (reached[guid]) continue;
    reached[guid] = true;
    for (const Joint& j : s.loose_joints) {
      if (j.left_frame_guid == guid) todo.push_back(j.right_frame_guid);
      if (j.right_frame_guid == guid) todo.push_back(j.left_frame_guid);
    }
  }
  std::vector<Selection> group;
  for (int i = 0; i < static_cast<int>(s.loose_frames.size()); ++i) {
    if (reached.count(s.loose_frames[i].guid)) {
      group.push_back({SelectionKind::kLooseFrame, 0, i});
    }
  }
  for (int i = 0; i < static_cast<int>(s.loose_sensor_modules.size()); ++i) {
    if (reached.count(s.loose_sensor_modules[i].guid)) {
      group.push_back({SelectionKind::kLooseSensorModule, 0, i});
    }
  }
  return group;
}

Eigen::Vector3d LoosePivot(const Scenario& s,
                           const std::vector<Selection>& group) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Selection& p : group) {
    sum += p.kind == SelectionKind::kLooseFrame
               ? s.loose_frames.at(p.index).position
               : s.loose_sensor_modules.at(p.index).position;
  }
  return group.empty() ? sum : Eigen::Vector3d(sum / group.size());
}

void MoveLooseGroup(Scenario* s, const std::vector<Selection>& group,
                    const GroundMove& move) {
  if (move.empty() || group.empty()) return;
  const Eigen::Isometry3d t = GroundTransform(LoosePivot(*s, group), move);
  for (const Selection& p : group) {
    if (p.kind == SelectionKind::kLooseFrame) {
      Frame& f = s->loose_frames.at(p.index);
      Place(t, &f.position, &f.quat_rotation);
    } else {
      TransformSensorModule(&s->loose_sensor_modules.at(p.index), t);
    }
  }
}

}  // namespace mrsim::studio

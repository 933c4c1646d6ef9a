#include "sim_core/codec/state_message.h"

#include <cmath>
#include <stdexcept>

namespace mrsim {
namespace {

pose_t ToPose(const Pose& pose) {
  pose_t msg{};
  for (int i = 0; i < 3; ++i) msg.position[i] = pose.position[i];
  // MuJoCo order (w, x, y, z).
  msg.orientation[0] = pose.orientation.w();
  msg.orientation[1] = pose.orientation.x();
  msg.orientation[2] = pose.orientation.y();
  msg.orientation[3] = pose.orientation.z();
  return msg;
}

Pose FromPose(const pose_t& msg) {
  Pose pose;
  pose.position =
      Eigen::Vector3d(msg.position[0], msg.position[1], msg.position[2]);
  pose.orientation = Eigen::Quaterniond(msg.orientation[0], msg.orientation[1],
                                        msg.orientation[2], msg.orientation[3]);
  return pose;
}

}  // namespace

int64_t SimTimeToUtime(double seconds) {
  return static_cast<int64_t>(std::llround(seconds * 1e6));
}

void SetLockStates(const std::vector<std::pair<std::string, bool>>& locks,
                   robot_state_t* msg) {
  msg->num_locks = static_cast<int32_t>(locks.size());
  msg->lock_names.resize(locks.size());
  msg->lock_attached.resize(locks.size());
  for (size_t i = 0; i < locks.size(); ++i) {
    msg->lock_names[i] = locks[i].first;
    msg->lock_attached[i] = locks[i].second;
  }
}

robot_state_t ToRobotStateMessage(const RobotState& state, int64_t seq) {
  robot_state_t msg{};
  msg.utime = SimTimeToUtime(state.time);
  msg.seq = seq;
  msg.robot = state.robot;
  msg.sim_time = state.time;

  msg.num_modules = static_cast<int32_t>(state.modules.size());
  msg.modules.reserve(state.modules.size());
  for (const Pose& p : state.modules) msg.modules.push_back(ToPose(p));

  msg.num_frames = static_cast<int32_t>(state.frames.size());
  msg.frames.reserve(state.frames.size());
  for (const Pose& p : state.frames) msg.frames.push_back(ToPose(p));

  msg.num_joints = static_cast<int32_t>(state.joints.size());
  msg.joints.reserve(state.joints.size());
  for (const JointState& j : state.joints) {
    joint_state_t js{};
    js.angle = j.angle;
    js.speed = j.speed;
    js.torque = j.torque;
    js.world = ToPose(j.world);
    msg.joints.push_back(js);
  }

  msg.num_sensor_modules = static_cast<int32_t>(state.sensor_modules.size());
  msg.sensor_modules.reserve(state.sensor_modules.size());
  for (const SensorModuleState& s : state.sensor_modules) {
    sensor_module_state_t sm{};
    sm.pose = ToPose(s.pose);
    sm.has_force = s.has_force;
    sm.force = s.force;
    sm.num_distances = static_cast<int8_t>(s.distances.size());
    sm.distance = s.distances;
    sm.distance_face.reserve(s.distances.size());
    for (size_t i = 0; i < s.distances.size(); ++i) {
      const int face = i < s.distance_faces.size() ? s.distance_faces[i] : -1;
      sm.distance_face.push_back(static_cast<int8_t>(face));
    }
    sm.num_readings = static_cast<int32_t>(s.readings.size());
    sm.readings.reserve(s.readings.size());
    for (const SensorReading& r : s.readings) {
      sensor_reading_t m{};
      m.kind = r.kind;
      m.face = static_cast<int8_t>(r.face);
      m.num_values = static_cast<int32_t>(r.values.size());
      m.values = r.values;
      sm.readings.push_back(std::move(m));
    }
    msg.sensor_modules.push_back(std::move(sm));
  }

  for (int i = 0; i < 3; ++i) {
    msg.com[i] = state.com[i];
    msg.com_velocity[i] = state.com_velocity[i];
  }
  msg.orientation[0] = state.orientation.w();
  msg.orientation[1] = state.orientation.x();
  msg.orientation[2] = state.orientation.y();
  msg.orientation[3] = state.orientation.z();
  msg.heading = state.heading;
  return msg;
}

RobotState FromRobotStateMessage(const robot_state_t& msg) {
  RobotState state;
  state.time = msg.sim_time;
  state.robot = msg.robot;
  for (const pose_t& p : msg.modules) state.modules.push_back(FromPose(p));
  for (const pose_t& p : msg.frames) state.frames.push_back(FromPose(p));
  for (const joint_state_t& js : msg.joints) {
    JointState j;
    j.angle = js.angle;
    j.speed = js.speed;
    j.torque = js.torque;
    j.world = FromPose(js.world);
    state.joints.push_back(j);
  }
  for (const sensor_module_state_t& sm : msg.sensor_modules) {
    SensorModuleState s;
    s.pose = FromPose(sm.pose);
    s.has_force = sm.has_force;
    s.force = sm.force;
    s.distances = sm.distance;
    for (int8_t f : sm.distance_face) s.distance_faces.push_back(f);
    for (const sensor_reading_t& r : sm.readings) {
      s.readings.push_back({r.kind, r.face, r.values});
    }
    state.sensor_modules.push_back(std::move(s));
  }
  state.com = Eigen::Vector3d(msg.com[0], msg.com[1], msg.com[2]);
  state.com_velocity = Eigen::Vector3d(msg.com_velocity[0], msg.com_velocity[1],
                                       msg.com_velocity[2]);
  state.orientation =
      Eigen::Quaterniond(msg.orientation[0], msg.orientation[1],
                         msg.orientation[2], msg.orientation[3]);
  state.heading = msg.heading;
  return state;
}

scene_state_t ToSceneStateMessage(const std::vector<SceneObjectState>& objects,
                                  double time, int64_t seq) {
  scene_state_t msg{};
  msg.utime = SimTimeToUtime(time);
  msg.seq = seq;
  msg.sim_time = time;
  msg.num_objects = static_cast<int32_t>(objects.size());
  msg.object_index.reserve(objects.size());
  msg.poses.reserve(objects.size());
  for (const SceneObjectState& o : objects) {
    msg.object_index.push_back(o.index);
    msg.poses.push_back(ToPose(o.pose));
  }
  return msg;
}

std::vector<SceneObjectState> FromSceneStateMessage(const scene_state_t& msg) {
  if (msg.num_objects < 0 ||
      msg.object_index.size() != static_cast<size_t>(msg.num_objects) ||
      msg.poses.size() != static_cast<size_t>(msg.num_objects)) {
    throw std::invalid_argument(
        "scene_state_t: num_objects disagrees with its arrays");
  }
  std::vector<SceneObjectState> objects(msg.poses.size());
  for (size_t i = 0; i < objects.size(); ++i) {
    objects[i].index = msg.object_index[i];
    objects[i].pose = FromPose(msg.poses[i]);
  }
  return objects;
}

}  // namespace mrsim

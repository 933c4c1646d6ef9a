// Known messages for the logger tests: a robot state whose every value is
// derived from (seq, index) so a test can check each cell it reads back.
#pragma once

#include <cmath>
#include <string>

#include "mrsim/robot_state_t.hpp"

namespace mrsim::testing {

// Value of field `k` of element `i` in message `seq`: distinct, with a full
// 17-digit mantissa so rounding would show.
inline double KnownValue(int64_t seq, int i, int k) {
  return std::sin(0.1 * static_cast<double>(seq) + 0.37 * i + 0.011 * k) *
         (1.0 + i);
}

inline pose_t KnownPose(int64_t seq, int i, int k0) {
  pose_t p;
  for (int k = 0; k < 3; ++k) p.position[k] = KnownValue(seq, i, k0 + k);
  for (int k = 0; k < 4; ++k) p.orientation[k] = KnownValue(seq, i, k0 + 3 + k);
  return p;
}

// A chain of `modules` modules with one hinge joint each, and
// `sensor_modules` sensor modules, each with a force sensor and distance
// sensors on faces 0 and 4.
inline robot_state_t KnownRobotState(int64_t seq, int modules,
                                     int sensor_modules,
                                     const std::string& robot = "snake") {
  robot_state_t m;
  m.utime = 1000 * seq + 17;  // 1 kHz, off the round millisecond
  m.seq = seq;
  m.robot = robot;
  m.sim_time = static_cast<double>(m.utime) / 1e6;
  m.num_modules = modules;
  m.num_frames = 2 * modules;
  m.num_joints = modules;
  for (int i = 0; i < modules; ++i) {
    m.modules.push_back(KnownPose(seq, i, 0));
    m.frames.push_back(KnownPose(seq, i, 10));
    m.frames.push_back(KnownPose(seq, i, 20));
    joint_state_t j;
    j.angle = KnownValue(seq, i, 30);
    j.speed = KnownValue(seq, i, 31);
    j.torque = KnownValue(seq, i, 32);
    j.world = KnownPose(seq, i, 40);
    m.joints.push_back(j);
  }
  m.num_sensor_modules = sensor_modules;
  for (int s = 0; s < sensor_modules; ++s) {
    sensor_module_state_t sm{};
    sm.pose = KnownPose(seq, 100 + s, 0);
    sm.has_force = true;
    sm.force = KnownValue(seq, 100 + s, 50);
    sm.num_distances = 2;
    sm.distance = {KnownValue(seq, 100 + s, 60), KnownValue(seq, 100 + s, 64)};
    sm.distance_face = {0, 4};
    m.sensor_modules.push_back(sm);
  }
  for (int k = 0; k < 3; ++k) {
    m.com[k] = KnownValue(seq, 200, k);
    m.com_velocity[k] = KnownValue(seq, 200, 3 + k);
  }
  for (int k = 0; k < 4; ++k) m.orientation[k] = KnownValue(seq, 200, 6 + k);
  m.heading = KnownValue(seq, 200, 10);
  m.num_locks = modules > 0 ? modules - 1 : 0;  // a chain's locks
  for (int k = 0; k < m.num_locks; ++k) {
    m.lock_names.push_back(robot + "/lock" + std::to_string(k));
    m.lock_attached.push_back(k % 2 == 0);  // both values in every row
  }
  return m;
}

}  // namespace mrsim::testing

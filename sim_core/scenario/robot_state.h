// A snapshot of one robot read from the physics: plain data that the
// processes turn into LCM messages and the optimiser scores.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace mrsim {

// World pose (Z up, metres).
struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

struct JointState {
  double angle = 0.0;   // rad
  double speed = 0.0;   // rad/s
  double torque = 0.0;  // N m, actuator torque
  Pose world;           // anchor position and child frame orientation
};

// One instance's values of a sensor kind read through MuJoCo's sensors
// (sensor_kind.h: the IMU), in the kind's channel order.
struct SensorReading {
  std::string kind;  // SensorKind::name, e.g. "imu"
  int face = -1;     // 0..5, or -1 when on no face
  std::vector<double> values;
};

struct SensorModuleState {
  Pose pose;
  bool has_force = false;
  double force = 0.0;               // N, magnitude
  std::vector<double> distances;    // m, one per distance sensor
  std::vector<int> distance_faces;  // face (0..5) of each distance sensor
  // The other kinds, in SensorKinds() order; an IMU's six values are
  // accel.x/y/z (m/s^2), gyro.x/y/z (rad/s) in the module's frame.
  std::vector<SensorReading> readings;
};

struct RobotState {
  double time = 0.0;  // s, simulation time
  std::string robot;
  std::vector<Pose> modules;       // module centres
  std::vector<Pose> frames;        // two per module: left, right
  std::vector<JointState> joints;  // hinge joints in chain order
  std::vector<SensorModuleState> sensor_modules;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();
  // The robot's orientation in the world: that of its head frame (module
  // 0's front frame, or the first sensor module when it has no modules),
  // so at t=0 it is the head frame's quatRotation in the design (which the
  // studio's heading ring turns). heading: yaw of the head frame's +x axis
  // about world z (rad, -pi..pi; 0 when that axis points straight up/down).
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  double heading = 0.0;
};

}  // namespace mrsim

// The C++ half of tests/python/test_state.py: steps a scenario with targets
// both sides compute exactly (small integers times 0.1), then prints the
// robot's state as C99 hex floats, one "name value" per line, so the test
// can check the Python State bit for bit.
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"

namespace {

void Print(const char* name, size_t i, double v) {
  std::printf("%s %zu %a\n", name, i, v);
}

void PrintPose(const char* name, size_t i, const mrsim::Pose& p) {
  const double v[7] = {p.position.x(),    p.position.y(),    p.position.z(),
                       p.orientation.w(), p.orientation.x(), p.orientation.y(),
                       p.orientation.z()};
  for (int k = 0; k < 7; ++k) Print(name, 7 * i + k, v[k]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: python_state_reference SCENARIO PERIODS\n");
    return 2;
  }
  try {
    mrsim::Physics physics(mrsim::ReadScenarioFile(argv[1]));
    const int periods = std::stoi(argv[2]);
    const int joints = physics.joint_count(0);
    for (int k = 0; k < periods; ++k) {
      std::vector<double> targets(joints);
      for (int j = 0; j < joints; ++j) {
        targets[j] = ((k * 7 + j * 3) % 11 - 5) * 0.1;
      }
      physics.SetJointTargets(0, targets);
      physics.Step(5);
    }
    const mrsim::RobotState s = physics.ReadRobotState(0);
    Print("time", 0, s.time);
    for (size_t i = 0; i < s.joints.size(); ++i) {
      Print("joint_angle", i, s.joints[i].angle);
      Print("joint_speed", i, s.joints[i].speed);
      Print("joint_torque", i, s.joints[i].torque);
      PrintPose("joint_pose", i, s.joints[i].world);
    }
    for (size_t i = 0; i < s.modules.size(); ++i) {
      PrintPose("module_pose", i, s.modules[i]);
    }
    for (size_t i = 0; i < s.frames.size(); ++i) {
      PrintPose("frame_pose", i, s.frames[i]);
    }
    for (size_t i = 0; i < s.sensor_modules.size(); ++i) {
      PrintPose("sensor_pose", i, s.sensor_modules[i].pose);
      Print("sensor_force", i,
            s.sensor_modules[i].has_force ? s.sensor_modules[i].force : NAN);
      const std::string name = "sensor_distance" + std::to_string(i);
      for (size_t j = 0; j < s.sensor_modules[i].distances.size(); ++j) {
        Print(name.c_str(), j, s.sensor_modules[i].distances[j]);
      }
    }
    for (int k = 0; k < 3; ++k) Print("com", k, s.com[k]);
    for (int k = 0; k < 3; ++k) Print("com_velocity", k, s.com_velocity[k]);
    const Eigen::Quaterniond& q = s.orientation;
    const double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
    for (int k = 0; k < 4; ++k) Print("orientation", k, wxyz[k]);
    Print("heading", 0, s.heading);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "python_state_reference: %s\n", e.what());
    return 1;
  }
  return 0;
}

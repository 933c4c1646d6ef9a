#include "gait_controller/process/joint_axes_spec.h"

#include <fmt/format.h>

#include <stdexcept>

#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {

JointAxesSpec::JointAxesSpec(const std::string& spec) {
  if (spec == "pitch" || spec == "yaw" || spec == "pitch-yaw" ||
      spec == "yaw-pitch") {
    pattern_ = spec;
    return;
  }
  for (char c : spec) {
    if (c == 'P' || c == 'p') {
      explicit_.push_back(Axis::kPitch);
    } else if (c == 'Y' || c == 'y') {
      explicit_.push_back(Axis::kYaw);
    } else {
      explicit_.clear();
      break;
    }
  }
  if (explicit_.empty()) {
    throw std::invalid_argument(fmt::format(
        "--axes: expected pitch, yaw, pitch-yaw, yaw-pitch or one letter P/Y "
        "per joint, got '{}'",
        spec));
  }
}

std::vector<Axis> JointAxesSpec::Expand(int joint_count) const {
  if (!explicit_.empty()) {
    if (static_cast<int>(explicit_.size()) != joint_count) {
      throw std::invalid_argument(
          fmt::format("--axes lists {} joints but the robot has {}",
                      explicit_.size(), joint_count));
    }
    return explicit_;
  }
  std::vector<Axis> axes;
  for (int j = 0; j < joint_count; ++j) {
    if (pattern_ == "pitch") {
      axes.push_back(Axis::kPitch);
    } else if (pattern_ == "yaw") {
      axes.push_back(Axis::kYaw);
    } else {
      const bool first = j % 2 == 0;
      const bool pitch = pattern_ == "pitch-yaw" ? first : !first;
      axes.push_back(pitch ? Axis::kPitch : Axis::kYaw);
    }
  }
  return axes;
}

std::vector<Axis> ScenarioJointAxes(const std::string& scenario_path,
                                    const std::string& robot) {
  const Scenario scenario = ReadScenarioFile(scenario_path);
  std::string names;
  for (const Robot& r : scenario.robots) {
    if (r.name == robot) {
      std::vector<Axis> axes;
      for (const Module& m : r.modules) {
        if (m.joint.type == JointType::kHinge) axes.push_back(m.axis);
      }
      return axes;
    }
    names += (names.empty() ? "" : ", ") + r.name;
  }
  throw std::invalid_argument(fmt::format(
      "{}: no robot named '{}' (it has: {})", scenario_path, robot, names));
}

}  // namespace mrsim

#include "gait_controller/gait_runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "gait_controller/cpg_feedback.h"

namespace mrsim {

std::vector<Axis> JointAxes(const Physics& physics, int robot) {
  if (robot < 0 || robot >= physics.robot_count()) {
    throw std::invalid_argument(
        fmt::format("no robot with index {} (the world has {})", robot,
                    physics.robot_count()));
  }
  std::vector<Axis> axes;
  for (int j = 0; j < physics.joint_count(robot); ++j) {
    axes.push_back(physics.joint_axis(robot, j));
  }
  return axes;
}

double BodyHeading(const RobotState& state) {
  const size_t n = state.modules.size();
  if (n < 2) return 0.0;
  const size_t half = n / 2;
  Eigen::Vector3d front = Eigen::Vector3d::Zero();
  Eigen::Vector3d back = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < half; ++i) front += state.modules[i].position;
  for (size_t i = n - half; i < n; ++i) back += state.modules[i].position;
  const Eigen::Vector3d d = (front - back) / static_cast<double>(half);
  return std::atan2(d.y(), d.x());
}

std::vector<double> ModuleRolls(const RobotState& state, double heading) {
  const Eigen::Vector3d axis(std::cos(heading), std::sin(heading), 0.0);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d side = axis.cross(up);
  std::vector<double> rolls;
  for (const Pose& m : state.modules) {
    Eigen::Vector3d u = m.orientation * Eigen::Vector3d::UnitZ();
    u -= u.dot(axis) * axis;
    rolls.push_back(std::atan2(u.dot(side), u.dot(up)));
  }
  return rolls;
}

GaitRunResult RunGait(Physics& physics, int robot, GaitController& controller,
                      double seconds, double control_period,
                      const GaitStepObserver& observer) {
  if (robot < 0 || robot >= physics.robot_count()) {
    throw std::invalid_argument(fmt::format("RunGait: no robot {}", robot));
  }
  const double ratio = control_period / physics.timestep();
  const int steps = static_cast<int>(std::lround(ratio));
  if (!std::isfinite(ratio) || steps < 1 || std::abs(ratio - steps) > 1e-6) {
    throw std::invalid_argument(fmt::format(
        "RunGait: control period {} s is not a whole number of {} s steps",
        control_period, physics.timestep()));
  }
  if (controller.joint_count() != physics.joint_count(robot)) {
    throw std::invalid_argument(
        fmt::format("RunGait: controller has {} joints, robot {} has {}",
                    controller.joint_count(), physics.robot_name(robot),
                    physics.joint_count(robot)));
  }
  const int periods =
      std::max(0, static_cast<int>(std::lround(seconds / control_period)));

  GaitRunResult result;
  RobotState state = physics.ReadRobotState(robot);
  result.com_start = state.com;
  result.heading_start = BodyHeading(state);
  double heading = result.heading_start;
  std::vector<double> rolls = ModuleRolls(state, heading);
  double last_time = physics.time();
  bool first = true;
  for (int k = 0; k < periods; ++k) {
    // The clock is the sim time, as mrsim-gait reads it from the state.
    const double now = physics.time();
    // A CPG gait with feedback reads the sensors, as mrsim-gait does.
    const std::optional<CpgParameters>& cpg = controller.active_gait().cpg;
    if (cpg && cpg->feedback_gain != 0) {
      controller.SetFeedback(CpgFeedback(state, *cpg));
    }
    const std::vector<double>& targets =
        controller.Update(first ? 0.0 : now - last_time);
    first = false;
    last_time = now;
    physics.SetJointTargets(robot, targets);
    physics.Step(steps);
    state = physics.ReadRobotState(robot);
    for (const JointState& j : state.joints) {
      result.energy += std::abs(j.torque * j.speed) * control_period;
    }
    const double h = BodyHeading(state);
    result.heading_change += std::remainder(h - heading, 2 * M_PI);
    heading = h;
    const std::vector<double> r = ModuleRolls(state, heading);
    double roll_step = 0;
    for (size_t i = 0; i < r.size(); ++i) {
      roll_step += std::remainder(r[i] - rolls[i], 2 * M_PI);
    }
    if (!r.empty()) result.roll_change += roll_step / r.size();
    rolls = r;
    if (observer) observer(physics, targets);
  }
  result.periods = periods;
  result.com_end = state.com;
  return result;
}

}  // namespace mrsim

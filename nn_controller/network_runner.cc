#include "nn_controller/network_runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "nn_controller/nn_observation.h"

namespace mrsim {

GaitRunResult RunNetwork(Physics& physics, int robot, MlpNetwork& network,
                         double seconds, double control_period,
                         const GaitStepObserver& observer) {
  if (robot < 0 || robot >= physics.robot_count()) {
    throw std::invalid_argument(fmt::format("RunNetwork: no robot {}", robot));
  }
  const double ratio = control_period / physics.timestep();
  const int steps = static_cast<int>(std::lround(ratio));
  if (!std::isfinite(ratio) || steps < 1 || std::abs(ratio - steps) > 1e-6) {
    throw std::invalid_argument(fmt::format(
        "RunNetwork: control period {} s is not a whole number of {} s steps",
        control_period, physics.timestep()));
  }
  if (network.shape().joints != physics.joint_count(robot)) {
    throw std::invalid_argument(
        fmt::format("RunNetwork: the network drives {} joints, robot {} has {}",
                    network.shape().joints, physics.robot_name(robot),
                    physics.joint_count(robot)));
  }
  const int periods =
      std::max(0, static_cast<int>(std::lround(seconds / control_period)));
  GaitRunResult result;
  RobotState state = physics.ReadRobotState(robot);
  result.com_start = state.com;
  NnObservation observation;
  for (int k = 0; k < periods; ++k) {
    // The state mrsim-sim would publish now, its sim time the clock.
    ObservationOf(state, &observation);
    const std::vector<double>& targets = network.Evaluate(observation);
    physics.SetJointTargets(robot, targets);
    physics.Step(steps);
    state = physics.ReadRobotState(robot);
    for (const JointState& j : state.joints) {
      result.energy += std::abs(j.torque * j.speed) * control_period;
    }
    if (observer) observer(physics, targets);
  }
  result.periods = periods;
  result.com_end = state.com;
  return result;
}

}  // namespace mrsim

#include "optimizer/episode/episode_controller.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "optimizer/episode/episode.h"
#include "optimizer/episode/lua_episode_controller.h"
#include "optimizer/episode/mlp_episode_controller.h"
#include "optimizer/episode/mlp_genes.h"

namespace mrsim {

std::unique_ptr<EpisodeController> MakeEpisodeController(
    const Problem& problem, const Genome& genome,
    const std::vector<Axis>& axes) {
  switch (problem.controller.kind) {
    case ControllerSpec::Kind::kGait:
      return nullptr;
    case ControllerSpec::Kind::kLua:
      return std::make_unique<LuaEpisodeController>(
          problem.controller, problem.genome, genome, axes);
    case ControllerSpec::Kind::kMlp:
      return std::make_unique<MlpEpisodeController>(MlpNetworkOfGenome(
          MlpShapeOf(problem.controller), problem.genome, genome));
  }
  throw ControllerError("unknown controller kind");
}

ControllerRunResult RunController(Physics& physics, int robot,
                                  EpisodeController& controller, double seconds,
                                  double control_period,
                                  const GaitStepObserver& observer) {
  if (robot < 0 || robot >= physics.robot_count()) {
    throw std::invalid_argument(
        fmt::format("RunController: no robot {}", robot));
  }
  const double ratio = control_period / physics.timestep();
  const int steps = static_cast<int>(std::lround(ratio));
  if (!std::isfinite(ratio) || steps < 1 || std::abs(ratio - steps) > 1e-6) {
    throw std::invalid_argument(fmt::format(
        "RunController: control period {} s is not a whole number of {} s "
        "steps",
        control_period, physics.timestep()));
  }
  const int periods =
      std::max(0, static_cast<int>(std::lround(seconds / control_period)));
  const size_t joints = static_cast<size_t>(physics.joint_count(robot));
  ControllerRunResult result;
  RobotState state = physics.ReadRobotState(robot);
  result.com_start = state.com;
  for (int k = 0; k < periods; ++k) {
    const std::vector<double>& targets =
        controller.Targets(physics.time(), state);
    if (targets.size() != joints) {
      throw ControllerError(
          fmt::format("the controller gave {} targets for {} joints",
                      targets.size(), joints));
    }
    physics.SetJointTargets(robot, targets);
    physics.Step(steps);
    state = physics.ReadRobotState(robot);
    for (const JointState& j : state.joints) {
      result.energy += std::abs(j.torque * j.speed) * control_period;
    }
    if (observer) observer(physics, targets);
  }
  result.com_end = state.com;
  return result;
}

}  // namespace mrsim

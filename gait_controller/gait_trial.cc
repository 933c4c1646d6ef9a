#include "gait_controller/gait_trial.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "gait_controller/gait_controller.h"
#include "gait_controller/gait_runner.h"
#include "sim_core/physics/physics.h"

namespace mrsim {

ChainPattern ChainFor(const Gait& gait, std::optional<Motion> motion) {
  const bool yaw =
      gait.parameters.amplitude_yaw != 0 || gait.parameters.offset_yaw != 0 ||
      (motion && *motion != Motion::kForward && *motion != Motion::kBackward);
  return yaw ? ChainPattern::kPitchYaw : ChainPattern::kPitch;
}

std::string ChainPatternName(ChainPattern pattern) {
  switch (pattern) {
    case ChainPattern::kPitch:
      return "pitch";
    case ChainPattern::kYaw:
      return "yaw";
    case ChainPattern::kPitchYaw:
      return "pitch-yaw";
  }
  return "?";
}

GaitOutcome MeasureGait(const Gait& gait, const GaitTrial& trial) {
  if (!(trial.settle >= 0 && trial.settle < trial.seconds)) {
    throw std::invalid_argument(
        fmt::format("MeasureGait: settle {} s must be in [0, {}) s",
                    trial.settle, trial.seconds));
  }
  Scenario scenario;
  if (trial.world) {
    scenario = *trial.world;
  } else {
    scenario.robots.push_back(MakeChain(trial.chain));
  }
  if (scenario.robots.empty()) {
    throw std::invalid_argument("MeasureGait: the world has no robot");
  }
  if (trial.passive_wheels) {
    for (Module& m : scenario.robots[0].modules) m.passive_wheels = true;
  }
  Physics physics(scenario);
  GaitController controller(JointAxes(physics, 0));
  controller.SetGait(gait);
  if (trial.motion) controller.SetMotion(*trial.motion, trial.strength);

  const GaitRunResult settle =
      RunGait(physics, 0, controller, trial.settle, trial.control_period);
  const GaitRunResult run =
      RunGait(physics, 0, controller, trial.seconds - trial.settle,
              trial.control_period);
  GaitOutcome out;
  out.body_length = trial.chain.modules * 2 * trial.chain.frame_size.x();
  out.displacement = run.com_end - run.com_start;
  const double timed = trial.seconds - trial.settle;
  out.speed = out.displacement.head<2>().norm() / timed / out.body_length;
  // Across the body as it lay when the timing started: a gait meant to go
  // straight ahead shows its sideways slip here.
  const Eigen::Vector2d left(-std::sin(run.heading_start),
                             std::cos(run.heading_start));
  out.drift = out.displacement.head<2>().dot(left) / timed / out.body_length;
  out.rise = out.displacement.z() / timed / out.body_length;
  out.heading_deg = (settle.heading_change + run.heading_change) * 180.0 / M_PI;
  out.roll_deg = (settle.roll_change + run.roll_change) * 180.0 / M_PI;
  return out;
}

}  // namespace mrsim

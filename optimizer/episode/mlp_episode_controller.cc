#include "optimizer/episode/mlp_episode_controller.h"

namespace mrsim {

const std::vector<double>& MlpEpisodeController::Targets(
    double t, const RobotState& state) {
  ObservationOf(state, &input_);
  input_.time = t;  // the sim time, as mrsim-nn reads the state's sim_time
  try {
    return network_.Evaluate(input_);
  } catch (const std::invalid_argument& e) {
    throw ControllerError(e.what());
  }
}

}  // namespace mrsim

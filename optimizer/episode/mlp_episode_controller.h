// A neural network (--controller mlp:H) as an episode's controller: one
// MlpNetwork per individual (mlp_genes.h), fed the robot's state each
// control period as mrsim-nn feeds it the state message (docs/nn.md), so
// the best network replayed against mrsim-sim in lockstep does what its
// episode did.
#pragma once

#include <vector>

#include "nn_controller/mlp_network.h"
#include "optimizer/episode/episode_controller.h"

namespace mrsim {

class MlpEpisodeController : public EpisodeController {
 public:
  explicit MlpEpisodeController(MlpNetwork network)
      : network_(std::move(network)) {}

  // Throws ControllerError when the robot has another joint count.
  const std::vector<double>& Targets(double t,
                                     const RobotState& state) override;

 private:
  MlpNetwork network_;
  NnObservation input_;  // reused each period
};

}  // namespace mrsim

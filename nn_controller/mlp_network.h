// A small multilayer perceptron that drives a robot's joints from its state
// (the inputs and layers of mlp_shape.h): the controller of mrsim-opt's
// `--controller mlp:H` and of mrsim-nn. Deterministic: the same weights,
// period and observation give the same targets bit for bit (plain loops
// and std::tanh, no threads).
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "nn_controller/mlp_shape.h"
#include "nn_controller/nn_observation.h"

namespace mrsim {

class MlpNetwork {
 public:
  // The clock period's bounds (s): what the period gene and a file take.
  static constexpr double kMinPeriod = 0.1;
  static constexpr double kMaxPeriod = 100.0;

  // Throws std::invalid_argument naming the field: a shape out of bounds,
  // weights not WeightCount() finite numbers, a period out of bounds.
  MlpNetwork(MlpShape shape, std::vector<double> weights, double period);

  // The joint targets (rad, within +-output_range) for `observation`.
  // Throws std::invalid_argument when it has another joint count. The
  // reference stays valid until the next call.
  const std::vector<double>& Evaluate(const NnObservation& observation);

  const MlpShape& shape() const { return shape_; }
  const std::vector<double>& weights() const { return weights_; }
  double period() const { return period_; }

 private:
  MlpShape shape_;
  std::vector<double> weights_;
  double period_;
  std::vector<int> sizes_;
  std::vector<Eigen::VectorXd> activations_;  // one per layer, reused
  std::vector<double> targets_;
};

}  // namespace mrsim

#include "nn_controller/mlp_network.h"

#include <fmt/format.h>

#include <cmath>

namespace mrsim {

MlpNetwork::MlpNetwork(MlpShape shape, std::vector<double> weights,
                       double period)
    : shape_(std::move(shape)), weights_(std::move(weights)), period_(period) {
  shape_.Validate();
  if (static_cast<long>(weights_.size()) != shape_.WeightCount()) {
    throw std::invalid_argument(
        fmt::format("weights: expected {} for this shape, got {}",
                    shape_.WeightCount(), weights_.size()));
  }
  for (size_t i = 0; i < weights_.size(); ++i) {
    if (!std::isfinite(weights_[i])) {
      throw std::invalid_argument(
          fmt::format("weights[{}]: expected a finite number", i));
    }
  }
  if (!(period_ >= kMinPeriod && period_ <= kMaxPeriod)) {
    throw std::invalid_argument(
        fmt::format("period: expected {} to {} s, got {}", kMinPeriod,
                    kMaxPeriod, period_));
  }
  sizes_ = shape_.LayerSizes();
  for (int size : sizes_)
    activations_.emplace_back(Eigen::VectorXd::Zero(size));
  targets_.resize(shape_.joints);
}

const std::vector<double>& MlpNetwork::Evaluate(const NnObservation& o) {
  const size_t joints = static_cast<size_t>(shape_.joints);
  if (o.angles.size() != joints || o.speeds.size() != joints) {
    throw std::invalid_argument(
        fmt::format("the network drives {} joints, the state has {}", joints,
                    o.angles.size()));
  }
  Eigen::VectorXd& x = activations_[0];
  int k = 0;
  for (size_t j = 0; j < joints; ++j) x[k++] = o.angles[j];
  for (size_t j = 0; j < joints; ++j) x[k++] = o.speeds[j];
  if (shape_.clock) {
    const double phase = 2 * M_PI * o.time / period_;
    x[k++] = std::sin(phase);
    x[k++] = std::cos(phase);
  }
  if (shape_.imu) {
    for (double v : o.orientation) x[k++] = v;
    for (double v : o.com_velocity) x[k++] = v;
  }
  for (int s = 0; s < shape_.sensors; ++s) {
    const double v = static_cast<size_t>(s) < o.sensor_values.size()
                         ? o.sensor_values[s]
                         : 0.0;
    x[k++] = std::isfinite(v) ? v : 0.0;
  }
  // Each layer: its weights row by row (one row per output), then biases.
  // A fixed summation order, the same in every build of one machine.
  const double* w = weights_.data();
  const size_t layers = sizes_.size() - 1;
  for (size_t l = 0; l < layers; ++l) {
    const Eigen::VectorXd& in = activations_[l];
    Eigen::VectorXd& out = activations_[l + 1];
    const int n_in = sizes_[l];
    const int n_out = sizes_[l + 1];
    const double* bias = w + static_cast<size_t>(n_in) * n_out;
    for (int r = 0; r < n_out; ++r) {
      double sum = bias[r];
      const double* row = w + static_cast<size_t>(r) * n_in;
      for (int c = 0; c < n_in; ++c) sum += row[c] * in[c];
      out[r] = std::tanh(sum);
    }
    w = bias + n_out;
  }
  const Eigen::VectorXd& y = activations_.back();
  for (size_t j = 0; j < joints; ++j) {
    targets_[j] = shape_.output_range * y[static_cast<int>(j)];
  }
  return targets_;
}

}  // namespace mrsim

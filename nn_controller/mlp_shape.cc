#include "nn_controller/mlp_shape.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <stdexcept>

namespace mrsim {

int MlpShape::InputCount() const {
  return 2 * joints + (clock ? 2 : 0) + (imu ? kImuInputs : 0) + sensors;
}

std::vector<int> MlpShape::LayerSizes() const {
  std::vector<int> sizes = {InputCount()};
  sizes.insert(sizes.end(), hidden.begin(), hidden.end());
  sizes.push_back(joints);
  return sizes;
}

long MlpShape::WeightCount() const {
  const std::vector<int> sizes = LayerSizes();
  long count = 0;
  for (size_t l = 1; l < sizes.size(); ++l) {
    count += (long{sizes[l - 1]} + 1) * sizes[l];
  }
  return count;
}

void MlpShape::Validate() const {
  if (joints < 1 || joints > kMaxJoints) {
    throw std::invalid_argument(
        fmt::format("joints: expected 1 to {}, got {}", kMaxJoints, joints));
  }
  if (sensors < 0 || sensors > kMaxSensors) {
    throw std::invalid_argument(
        fmt::format("sensors: expected 0 to {}, got {}", kMaxSensors, sensors));
  }
  if (hidden.size() > static_cast<size_t>(kMaxHiddenLayers)) {
    throw std::invalid_argument(
        fmt::format("hidden: expected at most {} layers, got {}",
                    kMaxHiddenLayers, hidden.size()));
  }
  for (int h : hidden) {
    if (h < 1 || h > kMaxLayerWidth) {
      throw std::invalid_argument(fmt::format(
          "hidden: a layer of {} (expected 1 to {})", h, kMaxLayerWidth));
    }
  }
  if (InputCount() < 1) {
    throw std::invalid_argument("inputs: the network reads nothing");
  }
  if (!(output_range > 0) || !std::isfinite(output_range)) {
    throw std::invalid_argument(fmt::format(
        "range: expected a finite angle > 0 rad, got {}", output_range));
  }
  // Each factor is bounded above, so the count cannot overflow.
  if (WeightCount() > kMaxWeights) {
    throw std::invalid_argument(
        fmt::format("weights: {} (at most {})", WeightCount(), kMaxWeights));
  }
}

std::vector<int> ParseHiddenLayers(const std::string& text,
                                   const std::string& field) {
  std::vector<int> hidden;
  size_t begin = 0;
  for (;;) {
    const size_t end = text.find(',', begin);
    const std::string part = text.substr(begin, end - begin);
    const bool digits =
        !part.empty() && part.size() <= 4 &&
        part.find_first_not_of("0123456789") == std::string::npos;
    const int size = digits ? std::stoi(part) : 0;
    if (size < 1 || size > MlpShape::kMaxLayerWidth) {
      throw std::invalid_argument(fmt::format(
          "{}: expected hidden layer sizes 1 to {} separated by commas "
          "(8 or 8,8), got '{}'",
          field, MlpShape::kMaxLayerWidth, text));
    }
    hidden.push_back(size);
    if (hidden.size() > static_cast<size_t>(MlpShape::kMaxHiddenLayers)) {
      throw std::invalid_argument(
          fmt::format("{}: at most {} hidden layers, got '{}'", field,
                      MlpShape::kMaxHiddenLayers, text));
    }
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return hidden;
}

std::string HiddenLayersText(const std::vector<int>& hidden) {
  return fmt::format("{}", fmt::join(hidden, ","));
}

}  // namespace mrsim

// The shape of a neural-network controller (docs/nn.md): which of the
// robot's state feeds it, its hidden layers, and the range its outputs (one
// joint target per hinge) are scaled to. The shape fixes the number of
// weights, so the optimiser's genome size follows from the robot's joint
// count and the hidden layer sizes (mlp:H, mlp:H1,H2).
//
// The input vector, in this order (all values as the state gives them,
// SI units, unscaled):
//   joints       angle of every hinge in chain order (rad), then the speed
//                of every hinge (rad/s): 2 * joints values;
//   clock        sin(2 pi t / period), cos(2 pi t / period), t the state's
//                sim time (s): 2 values when clock is on;
//   imu          the robot's orientation quaternion w, x, y, z, then its
//                centre-of-mass velocity x, y, z (m/s): 7 values when on;
//   sensors      the first `sensors` values of the sensor modules in order,
//                each module giving its force (N, when it has a force
//                sensor) then its distances (m); missing or non-finite
//                values are 0.
// Each hidden layer is tanh(W x + b); the output layer is
// range * tanh(W x + b), so every target lies within +-range.
#pragma once

#include <string>
#include <vector>

namespace mrsim {

struct MlpShape {
  // Bounds every reader checks before sizing a buffer from a file.
  static constexpr int kMaxJoints = 1024;
  static constexpr int kMaxSensors = 1024;
  static constexpr int kMaxHiddenLayers = 4;
  static constexpr int kMaxLayerWidth = 1024;
  static constexpr long kMaxWeights = long{1} << 22;  // 32 MiB of doubles
  static constexpr int kImuInputs = 7;

  int joints = 0;  // inputs 2 * joints, outputs joints
  bool clock = true;
  bool imu = false;
  int sensors = 0;
  std::vector<int> hidden;       // sizes of the hidden layers, input first
  double output_range = 1.5708;  // rad, as MakeChain's joint_limit

  int InputCount() const;
  // The layer sizes: inputs, the hidden layers, outputs.
  std::vector<int> LayerSizes() const;
  // Every layer's weights then biases (W row-major, one row per output).
  long WeightCount() const;
  // Throws std::invalid_argument naming the field and the bound.
  void Validate() const;

  bool operator==(const MlpShape& o) const {
    return joints == o.joints && clock == o.clock && imu == o.imu &&
           sensors == o.sensors && hidden == o.hidden &&
           output_range == o.output_range;
  }
};

// "8" or "8,8": the hidden layer sizes of mlp:H / mlp:H1,H2. Throws
// std::invalid_argument naming `field` and what was expected.
std::vector<int> ParseHiddenLayers(const std::string& text,
                                   const std::string& field);
std::string HiddenLayersText(const std::vector<int>& hidden);

}  // namespace mrsim

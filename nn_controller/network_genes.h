// The genes of a network controller (mrsim-opt --controller mlp:H): the
// clock period, then one gene per weight, w0, w1, ... in MlpNetwork's
// order (each layer's rows, then its biases), all within symmetric limits.
// With the shape they give the network an episode runs.
#pragma once

#include <string>
#include <vector>

#include "nn_controller/mlp_network.h"

namespace mrsim {

inline constexpr char kPeriodGene[] = "period";
// A weight gene's limits: +-kWeightGeneLimit. Inputs are O(1) (angles,
// sin/cos) and tanh saturates beyond a few units, so a wider range only
// adds flat fitness landscape.
inline constexpr double kWeightGeneLimit = 2.0;
// The period gene's limits and start (s): the gait presets' periods.
inline constexpr double kMinPeriodGene = 0.5;
inline constexpr double kMaxPeriodGene = 8.0;
inline constexpr double kStartPeriodGene = 3.0;

// "w<i>".
std::string WeightGeneName(long i);
// "period", "w0", ..., "w<WeightCount()-1>".
std::vector<std::string> NetworkGeneNames(const MlpShape& shape);
// True for "period" and "w<digits>".
bool IsNetworkGeneName(const std::string& name);

}  // namespace mrsim

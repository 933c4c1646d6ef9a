// What a neural-network controller reads of one robot state (the inputs
// listed in mlp_shape.h), filled alike from the physics in process
// (ObservationOf) and from a robot_state_t by mrsim-nn, so the optimiser's
// episode and the controller process feed the network the same numbers.
#pragma once

#include <vector>

#include "sim_core/scenario/robot_state.h"

namespace mrsim {

struct NnObservation {
  double time = 0.0;                     // s, the state's sim time
  std::vector<double> angles;            // rad, hinges in chain order
  std::vector<double> speeds;            // rad/s
  double orientation[4] = {1, 0, 0, 0};  // w, x, y, z
  double com_velocity[3] = {0, 0, 0};    // m/s
  // Per sensor module: its force (with a force sensor) then its distances.
  std::vector<double> sensor_values;
};

// Fills `out` (its vectors reused) from a state read from the physics.
void ObservationOf(const RobotState& state, NnObservation* out);

}  // namespace mrsim

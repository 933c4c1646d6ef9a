// Runs a network controller in closed loop with the physics in one
// process, exactly as mrsim-nn does against mrsim-sim in lockstep: each
// control period the network reads the robot's state at that sim time,
// its targets are applied, and the physics steps one period. The
// optimiser's mlp episodes and the tests are a few lines on top of this.
#pragma once

#include "gait_controller/gait_runner.h"
#include "nn_controller/mlp_network.h"
#include "sim_core/physics.h"

namespace mrsim {

// Runs round(seconds / control_period) periods; control_period must be a
// whole number (>= 1) of physics timesteps. Fills periods, com_start,
// com_end and energy of the result (the heading and roll measures are
// RunGait's). Throws std::invalid_argument on a bad robot index or period
// or a network of another joint count, and whatever Physics throws.
GaitRunResult RunNetwork(Physics& physics, int robot, MlpNetwork& network,
                         double seconds, double control_period = 0.01,
                         const GaitStepObserver& observer = {});

}  // namespace mrsim

// The sensor inputs of a CPG gait (CpgParameters, docs/gait.md "Sensory
// feedback"): each sensor module's reading goes to the joint nearest to
// it, as a number in [0, 1] the oscillators' feedback term scales.
#pragma once

#include <vector>

#include "gait_controller/cpg_parameters.h"
#include "sim_core/scenario/robot_state.h"

namespace mrsim {

// One input per joint of `state` (0 where no sensor module is nearest):
// a sensor module reads max(min(1, force / force_scale),
// max over its distance sensors of max(0, 1 - d / distance_range)) and
// gives it to the joint whose anchor is nearest to it (the larger input
// when two modules share a joint). A robot without sensors gives zeros.
std::vector<double> CpgFeedback(const RobotState& state,
                                const CpgParameters& parameters);

}  // namespace mrsim

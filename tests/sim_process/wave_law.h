// The test controller's law: joint targets as a pure function of the state
// message (sim time and joint angles), so the same states give the same
// targets in any process and the lockstep comparison is exact.
#pragma once

#include <cmath>
#include <vector>

#include "mrsim/robot_state_t.hpp"

namespace mrsim::testing {

inline std::vector<double> WaveTargets(const robot_state_t& state) {
  std::vector<double> targets(state.num_joints);
  const double t = state.sim_time;
  for (int i = 0; i < state.num_joints; ++i) {
    // Closed loop on purpose: any divergence in the state shows up.
    targets[i] = 0.8 * std::sin(2.0 * M_PI * t / 1.5 + 0.7 * i) +
                 0.05 * state.joints[i].angle;
  }
  return targets;
}

}  // namespace mrsim::testing

// mrsim.State: one robot's state (from Physics::ReadRobotState in process,
// or a robot_state_t from LCM) with numpy views of its parts and the
// logger's CSV columns.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mrsim/robot_state_t.hpp"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim::python {

struct StateObject {
  RobotState state;
  int64_t seq = -1;  // the state message's seq; -1 in process
  std::vector<std::pair<std::string, bool>> locks;
  std::vector<Axis> axes;  // empty when not known (states from LCM)

  // The robot_state_t mrsim-sim would publish for it.
  robot_state_t ToMessage() const;
  static StateObject FromMessage(const robot_state_t& msg);
};

}  // namespace mrsim::python

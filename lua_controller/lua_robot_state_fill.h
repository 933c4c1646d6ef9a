// The one conversion from a robot's state (sim_core's RobotState, as the
// physics reads it or as decoded from robot_state_t) to what a Lua
// script's step() is given: mrsim-lua and the optimiser's Lua episodes
// both call it, so a script sees the same state in either.
#pragma once

#include "lua_controller/lua_script.h"
#include "sim_core/scenario/robot_state.h"

namespace mrsim {

// Fills everything but `axes` (the caller knows the joint axes; they do
// not change during a run). Reuses `out`'s vectors. Non-finite force or
// distance values are left out of `force`/`distances` (a sensor that reads
// nothing), as they are in the readings' values.
void FillLuaRobotState(const RobotState& state, LuaRobotState* out);

}  // namespace mrsim

// BENCH lua_episode_efficiency: episodes per CPU second with a Lua
// controller (examples/optimise/serpenoid_params.lua, --controller lua:)
// over the built-in gait, on the flat task with 3 s episodes: what the
// sandboxed script costs an optimisation (target >= 0.8).
#pragma once

namespace mrsim {

// Prints the BENCH lines; returns 0, or 1 when an episode failed.
int BenchLuaEpisodeEfficiency();

}  // namespace mrsim

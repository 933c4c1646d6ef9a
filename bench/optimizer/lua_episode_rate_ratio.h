// BENCH lua_episode_rate_ratio: episodes per CPU second with a Lua
// controller (examples/optimise/serpenoid_params.lua, --controller lua:)
// over the built-in gait, on the flat task with 3 s episodes: what the
// sandboxed script costs an optimisation (target >= 0.8). A ratio of two
// workloads, not an efficiency: a script that drives the snake more
// cheaply than the gait could take it above 1.
#pragma once

namespace mrsim {

// Prints the BENCH lines; returns 0, or 1 when an episode failed.
int BenchLuaEpisodeRateRatio();

}  // namespace mrsim

// BENCH mlp_episode_efficiency: episodes per CPU second with a neural
// network (--controller mlp:16) over the built-in gait, on the flat task
// with 3 s episodes: what evaluating the network each control period costs
// an optimisation (target >= 0.9).
#pragma once

namespace mrsim {

// Prints the BENCH lines; returns 0, or 1 when an episode failed.
int BenchMlpEpisodeEfficiency();

}  // namespace mrsim

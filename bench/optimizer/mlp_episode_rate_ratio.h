// BENCH mlp_episode_rate_ratio: episodes per CPU second with a neural
// network (--controller mlp:16) over the built-in gait, on the flat task
// with 3 s episodes: what evaluating the network each control period costs
// an optimisation (target >= 0.9). A ratio of two workloads, not an
// efficiency: above 1 when the network's episodes cost less CPU than the
// gait's, as they do here (1.2-1.6).
#pragma once

namespace mrsim {

// Prints the BENCH lines; returns 0, or 1 when an episode failed.
int BenchMlpEpisodeRateRatio();

}  // namespace mrsim

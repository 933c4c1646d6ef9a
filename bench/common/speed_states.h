// The two speed states a shared virtual machine runs in, told apart by a
// baseline's own speed, so that a ratio can be taken within one of them.
//
// Why: on these 2-core VMs one thread runs in one of two states that last
// seconds to minutes (the in-process lockstep loop at about 58 or about 91
// sim s per s, its CPU time per sim s alike: a neighbour on the host's
// core, not our scheduling), and the share of rounds in the fast one
// drifted from 30 % to 91 % over four runs in a row. A loop that waits on
// round trips slows less than one that only computes, so the median of the
// pair ratios jumped with that share (0.739, 0.770, 0.694, 0.681) while the
// ratio within the fast state held (0.657, 0.648, 0.656, 0.666).
#pragma once

#include <vector>

namespace mrsim {

// Which repeats ran in the machine's fast state.
struct SpeedStates {
  // Whether the baseline's values fall in two clusters set well apart
  // (each holding at least a tenth of them); if not, every repeat counts
  // as fast and the rest is zero.
  bool two_states = false;
  double threshold = 0;  // between the clusters (Otsu's split)
  // Otsu's separability: the share of the values' variance that lies
  // between the clusters. A split normal gives 2/pi = 0.64 (in 600 values
  // at most 0.68; in 48, above 0.76 one time in a hundred), a uniform
  // 0.75; two states need 0.75 or more (0.80-0.88 in four runs of 600
  // here).
  double separability = 0;
  double slow_median = 0;  // the baseline's median in each cluster
  double fast_median = 0;
  std::vector<bool> fast;  // per repeat: in the fast state
  int fast_count() const;
};

// Classifies each repeat by `baseline[i]`, a speed (larger is faster).
SpeedStates FindSpeedStates(const std::vector<double>& baseline);

// The elements of `v` where `keep` is true (the same length).
std::vector<double> Select(const std::vector<double>& v,
                           const std::vector<bool>& keep);

}  // namespace mrsim

// One trial of the robust_gap benchmark: the same CMA-ES run (seed,
// budget) on a problem twice, once on the nominal world and once with
// robust fitness (the mean over K perturbed worlds), each best gait then
// replayed in other perturbed worlds. A gait's kept share is its mean
// fitness there over the fitness its optimiser reported for it (nominal:
// its one nominal episode; robust: its mean over the K training worlds):
// how much of what the optimiser promised survives a world that is not
// exactly the model.
#pragma once

#include <cstdint>
#include <string>

#include "optimizer/episode/episode.h"
#include "optimizer/search/genome.h"

namespace mrsim {

// A problem the benchmark trains on, by name, with why it is there.
struct RobustGapTask {
  std::string name;
  std::string why;
  Problem problem;     // nominal: robust.episodes == 0
  bool include_start;  // the start genome in generation 0
};

struct RobustGapBudget {
  int population = 8;
  int generations = 10;
  int robust_episodes = 8;         // K of --robust K
  int replay_worlds = 50;          // worlds each best is replayed in
  uint64_t replay_seed = 1234567;  // never a training seed
  int threads = 2;
};

struct KeptShare {
  double reported = 0.0;   // the fitness its optimisation reported (m)
  double nominal = 0.0;    // fitness in the nominal world (m)
  double perturbed = 0.0;  // mean over the replay worlds (m); a failed
                           // world counts 0
  double share = 0.0;      // perturbed / reported; 0 when reported <= 0
  Genome genes;
};

struct RobustGapResult {
  KeptShare nominal_gait;  // trained on the nominal world
  KeptShare robust_gait;   // trained with --robust K
  // robust_gait.share / nominal_gait.share; 0 when the nominal gait keeps
  // nothing measurable (see main.cc for how the figure treats that).
  double ratio = 0.0;
};

// snake11 with the forward gait's genes and no start genome (docs/physics.md,
// "Is a fast gait real?": the nominal best tumbles, a chaotic exploit), and
// the task suite's flat task with the seven sine genes.
std::vector<RobustGapTask> RobustGapTasks(const std::string& source_dir,
                                          double episode_seconds);

RobustGapResult RunRobustGapTrial(const RobustGapTask& task, uint64_t seed,
                                  const RobustGapBudget& budget);

}  // namespace mrsim

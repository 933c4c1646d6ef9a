// What "Watch best" and "Jump to generation" play in the live view: one
// individual of an optimisation (its genes as generations.csv lists them)
// built as the optimiser builds it (ApplyBodyGenes, GaitOfGenome), and
// written as the files mrsim-opt writes for its best, so the live run is
// one a user could start by hand.
#pragma once

#include <string>

#include "gait_controller/gait.h"
#include "sim_core/scenario/scenario.h"
#include "studio/live/live_runner.h"
#include "studio/live/optimise_session.h"

namespace mrsim::studio {

struct BestReplay {
  int generation = -1;  // as in generations.csv (the first is 0)
  double fitness = 0;
  Scenario scenario;  // the design with the body genes applied
  Gait gait;          // the base gait with the gait genes applied
  // The body differs from the design: the run must restart with
  // `scenario` (the gait alone can be sent to a running robot).
  bool body = false;
  std::string robot;  // the robot the genome applies to
};

// The individual of `row` for the optimisation `options` describes (its
// scenario file, genome and base gait). Genes the row lacks keep their
// start. Throws naming the file or gene that is wrong.
BestReplay MakeBestReplay(const OptimiseOptions& options,
                          const GenerationRow& row);

// Writes DIR/best_scenario.xml and DIR/best_gait.xml and returns `run` set
// to play them: that scenario, its robots, that gait file. Throws naming
// the file that cannot be written.
RunOptions WriteBestReplay(const BestReplay& replay, const std::string& dir,
                           RunOptions run);

}  // namespace mrsim::studio

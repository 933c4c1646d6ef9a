// Drives an algorithm generation by generation over a batch evaluator,
// writes the CSVs and a checkpoint after every generation, and resumes from
// the checkpoint: the recorded results are told to a fresh algorithm with
// the same seed, which re-creates its state exactly, so a killed and
// restarted run ends with the same result as an uninterrupted one.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "optimizer/search/algorithm.h"
#include "optimizer/search/batch_evaluator.h"
#include "sim_core/physics/checkpoint.h"

namespace mrsim {

struct GenerationReport {
  int generation = 0;   // completed generations (1-based)
  int generations = 0;  // planned
  int island = -1;      // the generation's island (-1: one population)
  double best = 0.0;    // of this generation
  double mean = 0.0;
  double best_so_far = 0.0;
  int failed = 0;  // failed individuals of this generation (in the mean)
  // Why they failed (EvalResult::error, "" when none was given): each
  // reason once with how many, the most frequent first (ties: the first
  // met first).
  std::vector<std::pair<std::string, int>> failed_reasons;
  long long evaluations = 0;  // total so far, cached ones included
  // Both from the evaluated generations after the first, once there are
  // any (the first also waits for workers and builds simulations).
  double evals_per_second = 0.0;
  int workers = 0;
  double eta_seconds = 0.0;  // < 0: not known yet (only replayed so far)
  bool replayed = false;     // taken from the checkpoint, not evaluated
};

// How RunOptimization runs: length, output folder, checkpoint identity and
// the progress callback (the studio's live run has its own RunOptions).
struct OptimizationRunOptions {
  int generations = 10;
  // Stop after this many generations (--jump-to); < 0: all; 0 is refused
  // (std::invalid_argument). When the checkpoint already holds more,
  // nothing in out_dir is rewritten.
  int stop_after = -1;
  // Output directory for checkpoint.txt, generations.csv, evaluations.csv;
  // empty: no files and no resume.
  std::string out_dir;
  // Identifies the problem (scenario, episode settings); a checkpoint made
  // for another problem or other settings is refused.
  std::string fingerprint;
  // What the fingerprint covers, in "key=value" lines (episode settings):
  // recorded in the checkpoint so a refusal names what changed.
  std::string described;
  // evaluations.csv ends with an `error` column: why a failed evaluation
  // failed (a controller's message). Off for the gait, whose files keep
  // their columns.
  bool error_column = false;
  std::function<void(const GenerationReport&)> progress;
};

struct RunResult {
  Genome best;
  EvalResult best_result;
  int best_generation = -1;
  int best_index = -1;
  int generations_done = 0;
  int generations_replayed = 0;
  long long evaluations = 0;
  bool wrote_files = false;
};

// A stop in the middle of a run: what the completed generations found
// (partial.generations_done may be 0: nothing completed).
class OptimizationInterrupted : public EvaluationInterrupted {
 public:
  explicit OptimizationInterrupted(RunResult partial)
      : EvaluationInterrupted("optimisation interrupted"),
        partial_(std::move(partial)) {}
  const RunResult& partial() const { return partial_; }

 private:
  RunResult partial_;
};

// A run checkpoint that cannot be used (other settings, corrupt) throws
// mrsim::CheckpointError (sim_core/physics/checkpoint.h), the one error type
// for every checkpoint file mrsim reads.

// Throws CheckpointError, OptimizationInterrupted (stop requested; the
// checkpoint holds every completed generation, the exception their best)
// or what the evaluator throws.
RunResult RunOptimization(const GenomeSpec& spec,
                          const AlgorithmSettings& settings,
                          BatchEvaluator& evaluator,
                          const OptimizationRunOptions& options);

}  // namespace mrsim

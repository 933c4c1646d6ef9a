// mrsim-opt as library code: its flags, the checks of its input, the run
// generation by generation with progress lines, and the files describing the
// best individual. For --farm the evaluator opens its own LCM connection
// (FarmLink), the one exception to "main owns the LCM": after a tcpq hub
// restart it must open a new one, which a borrowed connection cannot.
#pragma once

#include <cstdio>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <stdexcept>
#include <string>

#include "common/file_lock.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "optimizer/algorithm.h"
#include "optimizer/batch_evaluator.h"
#include "optimizer/episode.h"
#include "optimizer/optimization_run.h"

namespace CLI {
class App;
}

namespace mrsim {

// Everything the command line sets.
struct OptCommand {
  std::string scenario_path;
  std::string task;  // a task of the suite instead of a scenario (task.h)
  std::string genome_path;
  std::string genes;  // a built-in genome instead of --genome: sine | cpg
  std::string out_dir;
  std::string workers = "local:0";  // local:K threads (0: one per core)
  std::string gait_spec;            // empty: forward, or the task's own gait
  bool farm = false;
  std::string lcm_url;
  AuthFlags auth;
  bool allow_mixed_builds = false;
  double verify = 0.0;  // share of jobs run again elsewhere (FarmSettings)
  std::string prefix = "MRSIM_OPT";
  double job_timeout = 0.0;
  double worker_timeout = 2.0;
  int chunk_size = 0;  // 0: one Ethernet frame (FarmSettings)
  int generations = 20;
  int jump_to = -1;
  bool no_start = false;
  bool replay = false;
  bool quiet = false;
  AlgorithmSettings algorithm;
  EpisodeSettings episode;
};

// Registers every flag of mrsim-opt on `app`, writing into `command`.
void AddOptFlags(CLI::App& app, OptCommand& command);

// Bad input from the command line or a file (mrsim-opt exits with 2).
class OptInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The problem as every evaluator sees it: the decoded payload, so a local
// run and a farm run evaluate the very same bytes.
struct OptSetup {
  Problem problem;
  std::string payload;  // EncodeProblem
  std::string hash;     // FNV-1a 64 of the payload, hex
  int threads = 1;      // local threads
  // The run folder's lock (<out>/.mrsim-opt.lock), held while the run
  // writes there: two runs on one --out would overwrite each other's
  // checkpoint.
  std::shared_ptr<FileLock> lock;
};

// Reads and checks the scenario, genome, gait and settings; creates the
// output folder and locks it. Throws OptInputError naming the flag or file,
// or, when another run holds the folder, the process that does.
OptSetup PrepareOpt(const OptCommand& command);

// The evaluator the command asks for: local threads, or (--farm) the farm
// master on its own connection to --lcm-url (throws when it cannot open).
// `stop` abandons a batch; `log` gets the farm's events.
std::unique_ptr<BatchEvaluator> MakeOptEvaluator(
    const OptCommand& command, const OptSetup& setup,
    std::function<bool()> stop, std::function<void(const std::string&)> log);

// What a run left.
struct OptOutcome {
  // SIGINT/SIGTERM: the checkpoint holds the rest; result and the best
  // files are the completed generations' (when there are any).
  bool stopped = false;
  RunResult result;
  std::string best_dir;  // out_dir, or out_dir/jump-N for an older jump
  std::string launch;    // best_dir/replay.launch
};

// Runs (or resumes) the optimisation, writes best_gait.xml,
// best_scenario.xml, best_genome.xml and replay.launch, prints a progress
// line per generation and the summary on `out`, notes on `err`. Throws
// OptInputError for a checkpoint of other settings.
OptOutcome RunOpt(const OptCommand& command, const OptSetup& setup,
                  BatchEvaluator& evaluator, std::FILE* out, std::FILE* err);

// "generation 3 of 20: best ... | 5.20 evals/s | workers 2 | ETA 1m12s".
std::string FormatProgress(const GenerationReport& report);
// 75 -> "1m15s", 3700 -> "1h01m", unknown -> "?".
std::string FormatDuration(double seconds);

// mrsim (the launcher) next to this program, in build/bin, or "mrsim".
std::string FindLauncher();

}  // namespace mrsim

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
#include <utility>
#include <vector>

#include "common/file_lock.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "mrsim/opt_progress_t.hpp"
#include "optimizer/episode/episode.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/search/algorithm.h"
#include "optimizer/search/batch_evaluator.h"
#include "optimizer/search/optimization_run.h"
#include "optimizer/slurm/farm_cluster.h"

namespace CLI {
class App;
}

namespace mrsim {

// Everything the command line sets.
struct OptCommand {
  std::string scenario_path;
  std::string task;  // a task of the suite instead of a scenario (task.h)
  std::string genome_path;
  // A genome's text instead of a file (the design's <optimization><genome>,
  // opt_file_setup.h) and what names it in errors.
  std::string genome_text;
  std::string genome_source;
  // What --controller lua runs: the design's <run> script.
  std::string lua_source;
  std::string genes;  // a built-in genome instead of --genome: sine | cpg
  // --controller: gait | cpg | lua (the design's script) | lua:FILE |
  // mlp:H (controller_spec.h)
  std::string controller = "gait";
  std::string out_dir;
  std::string workers = "local:0";  // local:K threads (0: one per core)
  std::string gait_spec;            // empty: forward, or the task's own gait
  bool farm = false;
  std::string lcm_url;
  // --progress-url: where opt_progress_t goes (empty: not published).
  std::string progress_url;
  AuthFlags auth;
  bool allow_mixed_builds = false;
  double verify = 0.0;  // share of jobs run again elsewhere (FarmSettings)
  std::string prefix = kDefaultFarmPrefix;
  double job_timeout = 0.0;
  double worker_timeout = 2.0;
  int chunk_size = 0;  // 0: one Ethernet frame (FarmSettings)
  int generations = 20;
  int jump_to = -1;
  bool no_start = false;
  bool replay = false;
  bool quiet = false;
  // Optimise a scenario file whose parts overlap at the start (mrsim-sim
  // --allow-overlap's words); refused otherwise, as mrsim-sim refuses it.
  bool allow_overlap = false;
  int slurm = 0;  // --slurm N: workers submitted as one Slurm array job
  std::vector<std::string> slurm_options;  // --slurm-opt, sbatch options
  int hub_port = 0;                        // --hub PORT: start LCM's TCP hub
  AlgorithmSettings algorithm;
  EpisodeSettings episode;
  // --robust-gap NAME=VALUE (repeated): reality gap values set over the
  // design file's and RealityGap::Typical() (NAME a RealityGap field,
  // motor_noise); PrepareOpt applies and checks them.
  std::vector<std::string> robust_gap;
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

// Sets the --robust-gap NAME=VALUE words on `gap` and checks the result
// (RealityGap::Validate). Throws OptInputError naming the word or field.
void SetGapValues(const std::vector<std::string>& words, RealityGap* gap);

// Reads and checks the scenario, genome, gait and settings; creates the
// output folder and locks it. Throws OptInputError naming the flag or file,
// or, when another run holds the folder, the process that does.
OptSetup PrepareOpt(const OptCommand& command);

// --hub and --slurm: starts LCM's TCP hub and submits the workers' array
// job; nullptr when neither was asked for. Destroying it cancels the
// workers and stops the hub. Throws OptInputError when sbatch or the hub
// fails.
std::unique_ptr<FarmCluster> StartOptCluster(
    const OptCommand& command, std::function<void(const std::string&)> log);

// The evaluator the command asks for: local threads, or (--farm) the farm
// master on its own connection to --lcm-url, or to `cluster`'s hub (throws
// when it cannot open). `stop` abandons a batch; `log` gets the farm's
// events.
std::unique_ptr<BatchEvaluator> MakeOptEvaluator(
    const OptCommand& command, const OptSetup& setup,
    std::function<bool()> stop, std::function<void(const std::string&)> log,
    FarmCluster* cluster = nullptr);

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
// With --progress-url: opens a connection to it into *connection (its
// owner, main, keeps it while the run goes) and returns what publishes an
// opt_progress_t on <prefix>_PROGRESS there; without: an empty function.
// Throws OptInputError when LCM cannot open the URL.
std::function<void(const opt_progress_t&)> MakeProgressPublisher(
    const OptCommand& command, std::unique_ptr<lcm::LCM>* connection);

// With a `cluster`, each progress line ends with its Slurm array's counts.
// `publish` (optional) gets an opt_progress_t after every generation and
// when the run ends (opt_progress_reporter.h).
OptOutcome RunOpt(
    const OptCommand& command, const OptSetup& setup, BatchEvaluator& evaluator,
    std::FILE* out, std::FILE* err, FarmCluster* cluster = nullptr,
    const std::function<void(const opt_progress_t&)>& publish = {});

// "generation 3 of 20: best ... failed 2 (overlap at the start: robot
// 'snake' module 0 front frame / scene object 'ball') | 5.20 evals/s |
// workers 2 | ETA 1m12s".
std::string FormatProgress(const GenerationReport& report);
// Failed individuals by reason (GenerationReport::failed_reasons), each
// once: "overlap at the start: ..." when all share one, else the two most
// frequent with their counts and "; 3 for 2 other reasons"; "" when none
// gave a reason.
std::string FormatFailedReasons(
    const std::vector<std::pair<std::string, int>>& reasons);
// 75 -> "1m15s", 3700 -> "1h01m", unknown -> "?".
std::string FormatDuration(double seconds);

// mrsim (the launcher) next to this program, in build/bin, or "mrsim".
std::string FindLauncher();
// --replay: replaces this process with `mrsim launch <outcome.launch>`;
// returns (1) only when the launcher cannot be started, having said so.
int ExecReplay(const OptOutcome& outcome);
// Notes for the user: "mrsim-opt: <text>" on stderr, nothing with --quiet.
std::function<void(const std::string&)> OptLog(const OptCommand& command);
// `program` beside this one (mrsim-worker beside mrsim-opt), or `program`.
std::string FindSibling(const std::string& program);

}  // namespace mrsim

// The studio's Optimise panel behind the buttons: writes the edited genome,
// starts mrsim-opt (local threads or the farm) as a child process, and
// follows its progress from the files it writes (generations.csv) and the
// opt_progress_t messages it publishes (evaluations/s, workers, ETA; read
// over OptProgressLink, handled by OnProgress). "Watch best" takes the best
// so far from generations.csv while the run goes on; "Jump to generation"
// hands that generation's best over once it is there; a run alive without
// progress for too long gets a warning (StallWatch).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "launcher/launch_file.h"
#include "launcher/process_group.h"
#include "lcmtypes/runtime/outbox.h"
#include "mrsim/opt_progress_t.hpp"
#include "optimizer/episode/episode.h"
#include "optimizer/search/genome.h"
#include "studio/live/opt_progress_link.h"
#include "studio/live/stall_watch.h"

namespace mrsim::studio {

struct OptimiseOptions {
  std::string scenario_path;
  // A task of the suite (mrsim-opt --task) instead of scenario_path; its
  // gait is the base unless base_gait names one.
  std::string task;
  std::string out_dir;
  // What the genes drive (mrsim-opt --controller, docs/optimizer.md):
  // "gait" (the genome below), "lua" (lua_source, the design's script: its
  // declared params are the genes and `genome` is not used) or "mlp:H" /
  // "mlp:H1,H2" (a network's weights).
  std::string controller = "gait";
  std::string lua_source;
  GenomeSpec genome;
  std::string algorithm = "cmaes";  // a name of Algorithms()
  int generations = 10;
  int population = 8;
  unsigned seed = 1;
  double episode_s = 5;
  std::string base_gait = "forward";  // preset name or gait file (--gait)
  // The fitness (mrsim-opt --distance, --w-*; docs/optimizer.md).
  FitnessSettings fitness;
  // Robust fitness (mrsim-opt --robust K --robust-mode): each genome's
  // episode in K worlds of the reality gap (docs/optimizer.md); 0: the
  // nominal world only.
  RobustSettings robust;
  // The Run section's "allow overlap" box (mrsim-opt --allow-overlap): a
  // design whose parts overlap at the start is optimised anyway.
  bool allow_overlap = false;
  // Settings of the chosen algorithm by flag ("pso-c1" -> 2.0), each one
  // of its registry row's (AlgorithmInfo::settings); the rest keep
  // mrsim-opt's defaults.
  std::map<std::string, double> algorithm_settings;
  bool farm = false;    // mrsim-worker processes over LCM
  int islands = 1;      // populations taking turns (mrsim-opt --islands)
  std::string lcm_url;  // for the farm; empty: LCM's default
  // Where mrsim-opt publishes its progress (--progress-url); empty: lcm_url
  // (or LCM's default).
  std::string progress_url;
  int jump_to = -1;  // >= 0: stop after (or replay to) generation N
};

// One line of generations.csv.
struct GenerationRow {
  int generation = 0;
  double best = 0, mean = 0, worst = 0, best_so_far = 0;
  int failed = 0;
  std::map<std::string, double> genes;  // of the generation's best
};

struct OptimiseProgress {
  int generations = 0;              // asked for
  std::vector<GenerationRow> rows;  // completed, in order
  double evals_per_s = 0;
  int workers = 0;
  std::string eta;
  bool running = false;
  bool finished = false;  // ended by itself
  bool stopped = false;   // ended by Stop (the checkpoint keeps it)
  int exit_code = -1;
  // Why a finished run failed: mrsim-opt's last words.
  std::string failure;
  // The newest generation that had failed individuals, with mrsim-opt's
  // reasons ("generation 3: failed 2 (the body overlaps scene object
  // 'ball' ...)"); empty while none failed.
  std::string failed_note;
};

class OptimiseSession {
 public:
  explicit OptimiseSession(std::vector<std::string> search_path);
  ~OptimiseSession();
  OptimiseSession(const OptimiseSession&) = delete;
  OptimiseSession& operator=(const OptimiseSession&) = delete;

  // mrsim-opt's command line for `options` with the genome at genome_path.
  // Throws std::invalid_argument for options no run could use.
  static ProcessSpec Spec(const OptimiseOptions& options,
                          const std::string& genome_path);

  // Where Start writes the design's Lua script for mrsim-opt
  // (OUT/studio.controller.lua).
  static std::string ScriptPath(const OptimiseOptions& options);
  // The file mrsim-opt writes the best controller to, by what the genes
  // drive: best_gait.xml, best_controller.lua or best_network.xml.
  static std::string BestFileName(const OptimiseOptions& options);

  // Writes OUT/studio.genome.xml (the gait) or OUT/studio.controller.lua (a
  // Lua script) and starts mrsim-opt. Throws naming what
  // is wrong (genome, options, program not found).
  void Start(const OptimiseOptions& options, WallTime now = WallClock::now());
  void Stop();
  // Reads new progress; once per frame (timeout_ms: how long to wait for
  // the child's output first).
  void Poll(int timeout_ms = 0, WallTime now = WallClock::now());
  // One of mrsim-opt's progress messages (Poll hands them over); those of
  // another run folder are ignored.
  void OnProgress(const opt_progress_t& message,
                  WallTime now = WallClock::now());
  // The URL mrsim-opt publishes its progress on for `options`.
  static std::string ProgressUrl(const OptimiseOptions& options);
  const OptimiseProgress& progress() const { return progress_; }
  const std::vector<std::string>& console() const { return console_; }
  // The best individual so far, or of the first N generations after a
  // jump to N (nothing before the first generation).
  std::optional<GenerationRow> Best() const;
  // Its genes (empty before the first generation).
  std::map<std::string, double> BestGenes() const;
  // Generation `generation` (the first is 0) as generations.csv has it.
  const GenerationRow* Row(int generation) const;
  const OptimiseOptions& options() const { return options_; }
  // mrsim-opt's arguments for the run started last (empty before one):
  // what the form ran, for the window's tests and its layout dump.
  const std::vector<std::string>& command() const { return command_; }

  // Jump to generation N (counted from 1, as "generation k of n"): when
  // the run in options.out_dir already has it, its best is ready at once
  // (TakeReplay) and the run goes on; otherwise mrsim-opt starts with
  // --jump-to N (resuming from the checkpoint) and the best is ready when
  // that generation is written. Throws as Start.
  void Jump(int n, OptimiseOptions options, WallTime now = WallClock::now());
  // The generation a jump asked for, once, when it is there; nothing
  // before (or when the jump ended without reaching it: see console()).
  std::optional<GenerationRow> TakeReplay();
  bool replay_pending() const { return pending_replay_ >= 0; }

  // "no progress for 42 s: are workers alive? (workers 2)" while mrsim-opt
  // runs without a new generation for longer than the stall bound; empty
  // otherwise.
  std::string StallWarning(WallTime now = WallClock::now()) const;
  const StallWatch& stall_watch() const { return stall_; }

  // From one of mrsim-opt's progress lines ("generation 3 of 10: best ...
  // failed 2 (REASONS) | ..."), "generation 3: failed 2 (REASONS)"; empty
  // for a line that reports no failed individual.
  static std::string FailedNote(const std::string& progress_line);

  // Parses generations.csv text (header and rows); throws on a bad row.
  static std::vector<GenerationRow> ParseGenerations(const std::string& csv);

 private:
  void Line(const std::string& line);
  void ReadGenerations();

  std::vector<std::string> search_path_;
  OptimiseOptions options_;
  std::vector<std::string> command_;
  std::unique_ptr<ProcessGroup> group_;
  std::unique_ptr<OptProgressLink> progress_link_;
  std::string progress_dir_;  // out_dir as the messages carry it
  OptimiseProgress progress_;
  std::vector<std::string> console_;
  long long csv_size_ = -1;
  int progress_lines_ = 0;
  StallWatch stall_;
  int pending_replay_ = -1;  // generation (from 0) a jump waits for
  std::string last_line_;    // mrsim-opt's, for OptimiseProgress::failure
};

// Takes one of mrsim-opt's progress messages into `progress` (workers,
// evaluations/s, ETA) when it is about the run in `out_dir` (absolute, as
// the messages carry it); returns whether it was.
bool TakeOptProgress(const opt_progress_t& message, const std::string& out_dir,
                     OptimiseProgress* progress);

// The genome file to read for the path typed in the panel: a relative path
// that does not exist from the working folder is looked for beside the
// design (the studio started elsewhere than the repository still finds
// scenarios/forward_gait.genome.xml next to scenarios/case_study.xml),
// then in the installed data folder (common/data_dir.h).
std::string GenomePathFor(const std::string& genome_path,
                          const std::string& design_path);

}  // namespace mrsim::studio

// `mrsim run FILE` as library code: runs a saved design headless as the
// studio's Run does (the simulator and the controller saved in the file:
// its gait, its Lua script or an external controller), with the logger and
// the viewer writing into an output folder, and ends with the demo's
// summary line ("... moved X m"). main only parses and reports.
#pragma once

#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "launcher/launch_command.h"
#include "sim_core/scenario/scenario.h"

namespace CLI {
class App;
}

namespace mrsim {

// Everything `mrsim run` takes on the command line.
struct DesignRunFlags {
  std::string file;
  double duration = 0;               // s of sim time; 0: until Ctrl-C
  std::string out;                   // "": out/<file name without .xml> here
  std::string clock;                 // "": the file's <run>, else realtime
  std::optional<double> speed;       // unset: the file's <run>, else 1
  std::string lcm_url;               // "": $LCM_DEFAULT_URL, else LCM's default
  std::vector<std::string> without;  // process names: view, log, ...
  bool allow_overlap = false;
};

// Registers the flags of `mrsim run` on `app`.
void AddDesignRunFlags(CLI::App& app, DesignRunFlags& flags);

class DesignRun {
 public:
  // Reads the design and plans its run: every program found before any
  // starts, the saved Lua script written to OUT/<name>.controller.lua.
  // Throws ScenarioError for a bad file, OverlapError (overlap_check.h)
  // for parts that overlap at the start without allow_overlap,
  // UsageError for bad flags and LaunchError for a program not found.
  DesignRun(const std::string& argv0, const DesignRunFlags& flags);

  // What will run, in start order.
  const LaunchPlan& plan() const { return plan_; }
  // "FILE:LINE: path: warning: ..." about the design (ScenarioWarnings).
  const std::vector<std::string>& warnings() const { return warnings_; }
  // The output folder (absolute).
  const std::string& out_dir() const { return out_dir_; }

  // Runs the plan until the simulator ends (--duration) or `stop` returns
  // true, the processes' output prefixed with their names on `out`.
  // Returns 0 when every process ended cleanly, 1 otherwise (RunLaunch).
  int Run(const std::function<bool()>& stop, std::FILE* out) const;

  // After Run: the demo's line ("5.0 s: snake moved 0.120 m (dx ...)")
  // from the design and the checkpoint the simulator wrote at its end.
  // Throws CheckpointError when there is none (the simulator failed).
  std::string Summary() const;

 private:
  std::string scenario_path_;
  std::string out_dir_;
  std::string checkpoint_;
  Scenario scenario_;
  std::vector<std::string> warnings_;
  LaunchPlan plan_;
};

}  // namespace mrsim

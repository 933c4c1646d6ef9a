// mrsim-sim's command line: the flags (CLI11) and what they build, so main
// only parses, wires and runs.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/physics/physics.h"
#include "sim_core/sim_process/sim_options.h"

namespace mrsim {

struct SimCommandLine {
  std::string scenario_path;
  std::string lcm_url;
  AuthFlags auth;
  std::string load_checkpoint;
  bool no_state = false;
  bool no_spin = false;
  // Run a design whose parts overlap at the start (refused otherwise).
  bool allow_overlap = false;
  SimOptions options;
  // What the scenario's run settings set and which controllers to start,
  // for stderr; empty when the file has none (LoadPhysics fills it).
  std::string run_note;
  // "mrsim-sim: FILE:LINE: path: warning: ..." lines about the scenario
  // (ScenarioWarnings), for stderr (LoadPhysics fills it).
  std::vector<std::string> warnings;

  // Declares every flag of mrsim-sim (and --version) on `app`.
  void AddFlags(CLI::App& app);
  // Fills options from the parsed flags and checks them. Throws UsageError.
  void Finish();
  // The physics to run: the scenario, the checkpoint, or the checkpoint
  // checked against the scenario. The scenario's run settings become the
  // defaults of the flags not given (ApplyRunSettings). A scenario whose
  // parts overlap at the start is refused naming them, unless
  // --allow-overlap. Throws UsageError naming the file.
  std::unique_ptr<Physics> LoadPhysics();
  // A design's run settings (<run>) for every run flag the command line
  // did not give: --clock (lockstep for an external controller), --rate,
  // --speed and, in lockstep, --controllers (the external name, or the
  // names the studio gives its gait and Lua nodes: gait-<robot>,
  // lua-<robot>). Checks the result; fills run_note. Throws UsageError.
  void ApplyRunSettings(const Scenario& scenario);

  // With --load-checkpoint, the line that says what was loaded: the file,
  // its robots and the sim time it continues from; "" otherwise.
  std::string LoadLine(const Physics& physics) const;

 private:
  // The run flags, to tell given (count() > 0) from defaulted.
  CLI::Option* clock_flag_ = nullptr;
  CLI::Option* rate_flag_ = nullptr;
  CLI::Option* speed_flag_ = nullptr;
  CLI::Option* controllers_flag_ = nullptr;
};

}  // namespace mrsim

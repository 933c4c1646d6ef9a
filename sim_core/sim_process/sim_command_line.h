// mrsim-sim's command line: the flags (CLI11) and what they build, so main
// only parses, wires and runs.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/physics.h"
#include "sim_core/sim_process/sim_options.h"

namespace mrsim {

struct SimCommandLine {
  std::string scenario_path;
  std::string lcm_url;
  AuthFlags auth;
  std::string load_checkpoint;
  bool no_state = false;
  bool no_spin = false;
  SimOptions options;

  // Declares every flag of mrsim-sim (and --version) on `app`.
  void AddFlags(CLI::App& app);
  // Fills options from the parsed flags and checks them. Throws UsageError.
  void Finish();
  // The physics to run: the scenario, the checkpoint, or the checkpoint
  // checked against the scenario. Throws UsageError naming the file.
  std::unique_ptr<Physics> LoadPhysics() const;
  // With --load-checkpoint, the line that says what was loaded: the file,
  // its robots and the sim time it continues from; "" otherwise.
  std::string LoadLine(const Physics& physics) const;
};

}  // namespace mrsim

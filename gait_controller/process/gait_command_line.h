// mrsim-gait's command line: the flags (CLI11) and what they build (node
// options, the initial gait, where the joint axes come from), so main only
// parses, wires and runs.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "gait_controller/gait.h"
#include "gait_controller/process/gait_node.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/scenario.h"

namespace mrsim {

struct GaitCommandLine {
  std::string robot;
  std::string lcm_url;
  AuthFlags auth;
  std::string gait_spec = "forward";
  std::string scenario_path;
  std::string axes_text;
  std::string name;
  bool keyboard = false;
  std::string resume;  // a checkpoint whose saved gait state to continue
  GaitNodeOptions options;

  // Filled by Finish().
  Gait initial;
  std::function<std::vector<Axis>(int)> axes_for;
  // A warning for stderr (no --scenario or --axes), or empty.
  std::string warning;

  // Declares every flag of mrsim-gait (and --version) on `app`.
  void AddFlags(CLI::App& app);
  // Resolves the gait and the joint axes, checks the flags (stdin must be a
  // terminal for --keyboard). Throws UsageError naming the flag.
  void Finish(bool stdin_is_terminal);
  // "mrsim-gait: robot R, sender S, gait G, listening on ... and ...".
  std::string StartLine() const;
};

}  // namespace mrsim

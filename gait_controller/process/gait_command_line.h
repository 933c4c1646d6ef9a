// mrsim-gait's command line: the flags (CLI11) and what they build (node
// options, the initial gait, where the joint axes come from), so main only
// parses, wires and runs.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "gait_controller/gait.h"
#include "gait_controller/process/controller_flags.h"
#include "gait_controller/process/gait_node.h"
#include "lcmtypes/runtime/usage_error.h"

namespace mrsim {

struct GaitCommandLine {
  // --robot, --lcm-url, --scenario, --axes, --name, ...; after Finish() its
  // axes_for and warning.
  ControllerFlags controller{"gait"};
  std::string gait_spec = "forward";
  bool keyboard = false;
  std::string resume;  // a checkpoint whose saved gait state to continue
  GaitNodeOptions options;

  // Filled by Finish().
  Gait initial;

  // Declares every flag of mrsim-gait (and --version) on `app`.
  void AddFlags(CLI::App& app);
  // Resolves the gait and the joint axes, checks the flags (stdin must be a
  // terminal for --keyboard). Throws UsageError naming the flag.
  void Finish(bool stdin_is_terminal);
  // "mrsim-gait: robot R, sender S, gait G, listening on ... and ...".
  std::string StartLine() const;
};

}  // namespace mrsim

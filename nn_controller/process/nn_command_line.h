// mrsim-nn's command line: the flags (CLI11) and what they build (the node
// options and the network read from --net), so main only parses, wires and
// runs.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "gait_controller/process/controller_flags.h"
#include "nn_controller/network_file.h"
#include "nn_controller/process/nn_node.h"

namespace mrsim {

struct NnCommandLine {
  // --robot, --lcm-url, --name, --rate, --exit-with-sim, ...
  ControllerFlags controller{"nn"};
  std::string net_path;
  bool check_only = false;
  NnNodeOptions options;

  // Filled by Finish().
  std::optional<NetworkFile> net;

  void AddFlags(CLI::App& app);
  // Reads --net (throws NetworkFileError naming its line and field) and
  // resolves the rest (throws UsageError naming the flag).
  void Finish();
  std::string StartLine() const;
};

}  // namespace mrsim

// mrsim-studio's command line: what main parses before opening a window.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

struct StudioFlags {
  std::string scenario;    // file to open (or create), "" for none
  std::string screenshot;  // --screenshot PNG, "" for the window
  std::string key_file;    // --key-file
  std::string select;      // --select NAME (selection_name.h), "" for none
  // --drag X0 Y0 X1 Y1: the screenshot shows the left button pressed at
  // (X0, Y0) and dragged to (X1, Y1), still held; empty for none.
  std::vector<int> drag;
  AppOptions options;
};

// Adds every flag of mrsim-studio to `cli`, writing into `flags`.
void AddStudioFlags(CLI::App* cli, StudioFlags* flags);

// The window's options: flags.options, with "New robot from template" up
// at the start when no SCENARIO was given (docs/studio.md).
AppOptions StartOptions(const StudioFlags& flags);

// The design to open (an empty one without SCENARIO) with --select
// applied. Throws UsageError for a name it does not have, ScenarioError
// for a file that cannot be read.
Design OpenDesign(const StudioFlags& flags);

}  // namespace mrsim::studio

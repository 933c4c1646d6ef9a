// mrsim-studio's command line: what main parses before opening a window.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

struct StudioFlags {
  std::string scenario;    // file to open (or create), "" for none
  std::string screenshot;  // --screenshot PNG, "" for the window
  std::string key_file;    // --key-file
  AppOptions options;
};

// Adds every flag of mrsim-studio to `cli`, writing into `flags`.
void AddStudioFlags(CLI::App* cli, StudioFlags* flags);

}  // namespace mrsim::studio

// `mrsim launch` as library code: its flags, the plan (the launch file read
// with --set and --without, every program found before any starts) and
// running that plan as one process group. main only parses and reports.
#pragma once

#include <cstdio>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "launcher/launch_file.h"

namespace CLI {
class App;
}

namespace mrsim {

// Everything `mrsim launch` takes on the command line.
struct LaunchCommand {
  std::string file;
  std::vector<std::string> sets;     // NAME=VALUE
  std::vector<std::string> without;  // process names
  bool dry_run = false;
  std::string key_file;  // handed to every process as MRSIM_KEY_FILE
};

// Registers the launch subcommand's arguments on `launch`.
void AddLaunchFlags(CLI::App& launch, LaunchCommand& command);

// `mrsim --help`'s description: the subcommands and the tools.
const char* FrontDoorHelp();

// What will run: each enabled process with the program path found for it.
struct LaunchPlan {
  std::string name;  // the launch file's
  std::vector<std::pair<ProcessSpec, std::string>> processes;
};

// `file` as given when it is a path or is there; a bare name that is not
// (`mrsim launch demo.launch` on an installed mrsim) is looked up among the
// bundled launch files (DataDir()/launch); else `file`, for the error.
std::string FindLaunchFile(const std::string& file);

// Reads the file with the overrides, leaves out --without processes and
// finds every program on ProgramSearchPath(argv0), so a typo starts
// nothing. Throws LaunchError naming the file (and line) and the problem.
LaunchPlan PlanLaunch(const std::string& argv0, const LaunchCommand& command);

// --dry-run: one line per process, arguments quoted so the line can be
// pasted into a shell.
void PrintPlan(const LaunchPlan& plan, std::ostream& out);

// Starts the plan's processes (each after its delay) and forwards their
// output to `out` until a required one ends, every one has ended or `stop`
// returns true; then stops the rest. Returns 0 when every process ended
// cleanly, 1 otherwise.
int RunLaunch(const LaunchPlan& plan, const std::function<bool()>& stop,
              std::FILE* out);

// `mrsim TOOL ARGS...`: replaces this process with mrsim-TOOL. Returns only
// by throwing: LaunchError when there is no such tool, std::runtime_error
// when it cannot be run.
[[noreturn]] void ExecTool(const std::string& argv0, const std::string& tool,
                           std::vector<std::string> args);

}  // namespace mrsim

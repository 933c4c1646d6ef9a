// mrsim: the front door. `mrsim launch FILE` starts a set of processes from
// a launch file; `mrsim TOOL ARGS...` runs mrsim-TOOL.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <map>
#include <thread>

#include "common/version.h"
#include "launcher/launch_file.h"
#include "launcher/process_group.h"
#include "launcher/program_locator.h"
#include "launcher/shell_quote.h"
#include "lcmtypes/runtime/stop_signal.h"

namespace {

int Launch(const std::string& argv0, const std::string& file,
           const std::vector<std::string>& sets,
           const std::vector<std::string>& without, bool dry_run) {
  std::map<std::string, std::string> overrides;
  for (const auto& s : sets) {
    const size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw mrsim::LaunchError("--set " + s + ": expected NAME=VALUE");
    }
    overrides[s.substr(0, eq)] = s.substr(eq + 1);
  }
  mrsim::LaunchFile launch = mrsim::ReadLaunchFile(file, overrides);
  for (const auto& name : without) {
    bool found = false;
    for (auto& p : launch.processes) {
      if (p.name == name) {
        p.enabled = false;
        found = true;
      }
    }
    if (!found) {
      throw mrsim::LaunchError(file + ": --without " + name +
                               ": no process of that name");
    }
  }

  // Resolve every program before starting any, so a typo starts nothing.
  const auto search = mrsim::ProgramSearchPath(argv0);
  std::vector<std::pair<mrsim::ProcessSpec, std::string>> plan;
  for (const auto& p : launch.processes) {
    if (!p.enabled) continue;
    try {
      plan.emplace_back(p, mrsim::FindProgram(p.program, search));
    } catch (const std::runtime_error& e) {
      // A typo in the file: bad input, named where it is.
      throw mrsim::LaunchError(file + ":" + std::to_string(p.line) +
                               ": process '" + p.name + "': " + e.what());
    }
  }
  if (plan.empty())
    throw mrsim::LaunchError(file + ": every process is left out");

  if (dry_run) {
    for (const auto& [spec, path] : plan) {
      std::cout << spec.name << (spec.required ? " (required)" : "") << ": "
                << path;
      for (const auto& a : spec.args) std::cout << " " << mrsim::ShellQuote(a);
      std::cout << "\n";
    }
    return 0;
  }

  mrsim::InstallStopHandlers();
  mrsim::ProcessGroup group(stdout);
  group.Say("launch " + launch.name + ": " + std::to_string(plan.size()) +
            " processes; Ctrl-C stops them all");
  std::string ended;
  for (const auto& [spec, path] : plan) {
    const auto start = std::chrono::steady_clock::now();
    while (spec.delay_s > 0 && !mrsim::StopRequested() && ended.empty() &&
           std::chrono::steady_clock::now() - start <
               std::chrono::duration<double>(spec.delay_s)) {
      ended = group.Poll(20);
    }
    if (mrsim::StopRequested() || !ended.empty()) break;
    group.Start(spec, path);
  }
  while (ended.empty() && !mrsim::StopRequested() && group.AnyRunning()) {
    ended = group.Poll(100);
  }
  if (mrsim::StopRequested()) {
    group.Say("stop requested, stopping every process");
  } else if (!ended.empty()) {
    group.Say(ended + " ended, stopping the others");
  }
  group.StopAll(10.0);
  group.Say("all stopped:\n" + group.Summary());
  return group.AllClean() ? 0 : 1;
}

int RunTool(const std::string& argv0, const std::string& tool,
            std::vector<std::string> args) {
  const std::string path =
      mrsim::FindProgram("mrsim-" + tool, mrsim::ProgramSearchPath(argv0));
  args.insert(args.begin(), path);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(path.c_str(), argv.data());
  throw std::runtime_error("cannot run " + path);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    // `mrsim TOOL ...` passes everything after TOOL through untouched.
    if (argc >= 2 && argv[1][0] != '-' && std::string(argv[1]) != "launch") {
      return RunTool(argv[0], argv[1],
                     std::vector<std::string>(argv + 2, argv + argc));
    }
    CLI::App app{
        "mrsim: modular robot simulator front door.\n"
        "  mrsim launch FILE    start the processes of a launch file\n"
        "  mrsim TOOL ARGS...   run mrsim-TOOL (scenario, sim, gait, "
        "opt, worker, log, plot, view)"};
    app.set_version_flag("--version", std::string("mrsim ") + mrsim::kVersion);
    app.require_subcommand(1);
    auto* launch =
        app.add_subcommand("launch", "Start the processes of a launch file");
    std::string file;
    std::vector<std::string> sets;
    std::vector<std::string> without;
    bool dry_run = false;
    launch->add_option("file", file, "Launch file (XML)")->required();
    launch->add_option("--set", sets, "Override an <arg>: NAME=VALUE");
    launch->add_option("--without", without, "Leave a process out (by name)");
    launch->add_flag("--dry-run", dry_run,
                     "Print the resolved commands and start nothing");
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return app.exit(e) == 0 ? 0 : 2;
    }
    return Launch(argv[0], file, sets, without, dry_run);
  } catch (const mrsim::LaunchError& e) {
    std::fprintf(stderr, "mrsim: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim: %s\n", e.what());
    return 1;
  }
}

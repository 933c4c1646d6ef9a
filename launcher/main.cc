// mrsim: the front door. `mrsim launch FILE` starts a set of processes from
// a launch file; `mrsim TOOL ARGS...` runs mrsim-TOOL (launch_command.h).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "common/cli_exit.h"
#include "common/version.h"
#include "launcher/keygen_command.h"
#include "launcher/launch_command.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "keygen") {
    return mrsim::RunKeygen(argc, argv);
  }
  try {
    // `mrsim TOOL ...` passes everything after TOOL through untouched.
    if (argc >= 2 && argv[1][0] != '-' && std::string(argv[1]) != "launch") {
      mrsim::ExecTool(argv[0], argv[1],
                      std::vector<std::string>(argv + 2, argv + argc));
    }
    CLI::App app{mrsim::FrontDoorHelp()};
    app.set_version_flag("--version", std::string("mrsim ") + mrsim::kVersion);
    app.require_subcommand(1);
    mrsim::LaunchCommand command;
    mrsim::AddLaunchFlags(
        *app.add_subcommand("launch", "Start the processes of a launch file"),
        command);
    if (argc == 1) {  // what there is, rather than "subcommand required"
      std::cerr << app.help();
      return 2;
    }
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return mrsim::CliParseExit(app, e);
    }
    mrsim::ExportLaunchKey(command.key_file);
    const mrsim::LaunchPlan plan = mrsim::PlanLaunch(argv[0], command);
    if (command.dry_run) {
      mrsim::PrintPlan(plan, std::cout);
      return 0;
    }
    mrsim::InstallStopHandlers();
    return mrsim::RunLaunch(
        plan, [] { return mrsim::StopRequested(); }, stdout);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim: %s\n", e.what());
    // A bad key file or launch file is bad usage; anything else a failure.
    const bool usage = dynamic_cast<const mrsim::UsageError*>(&e) ||
                       dynamic_cast<const mrsim::LaunchError*>(&e);
    return usage ? 2 : 1;
  }
}

// mrsim-worker: evaluates episodes for any mrsim-opt master on the LCM
// network; start any number on any hosts, at any time (docs/optimizer.md).
#include <signal.h>

#include <CLI/CLI.hpp>
#include <cstdio>

#include "common/cli_exit.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"
#include "optimizer/process/worker_command.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-worker: run optimiser episodes for mrsim-opt --farm"};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-worker"));
  mrsim::WorkerCommand command;
  mrsim::AddWorkerFlags(app, command);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& err) {
    return mrsim::CliParseExit(app, err);
  }
  try {
    mrsim::CheckWorkerCommand(command);
    mrsim::InstallStopHandlers();
    signal(SIGPIPE, SIG_IGN);  // a tcpq hub that goes away: re-connect
    mrsim::RunWorkerCommand(command, stdout, mrsim::StopRequested);
    return 0;
  } catch (const mrsim::UsageError& err) {  // the key file
    std::fprintf(stderr, "mrsim-worker: %s\n", err.what());
    return 2;
  } catch (const mrsim::WorkerInputError& err) {
    std::fprintf(stderr, "mrsim-worker: %s\n", err.what());
    return 2;
  } catch (const std::exception& err) {
    std::fprintf(stderr, "mrsim-worker: %s\n", err.what());
    return 1;
  }
}

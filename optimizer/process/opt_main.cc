// mrsim-opt: optimises a gait (and body) for a scenario on local threads or
// a farm of mrsim-worker processes; checkpoints every generation and goes
// on when run again (docs/optimizer.md). The work is in opt_command.h.
#include <fmt/format.h>
#include <signal.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <memory>

#include "common/cli_exit.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"
#include "optimizer/process/opt_command.h"
#include "optimizer/process/opt_file_setup.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-opt: optimise a gait and body for a scenario"};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-opt"));
  mrsim::OptCommand command;
  mrsim::AddOptFlags(app, command);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& err) {
    return mrsim::CliParseExit(app, err);
  }
  try {
    mrsim::InstallStopHandlers();
    command.auth.ExportToChildren();       // --replay's processes
    mrsim::ApplyFileSetup(app, &command);  // the design's <optimization>
    const mrsim::OptSetup setup = mrsim::PrepareOpt(command);
    signal(SIGPIPE, SIG_IGN);  // a tcpq hub that goes away: re-connect
    const auto log = mrsim::OptLog(command);
    // Declared before the evaluator: the workers are cancelled after it.
    auto cluster = mrsim::StartOptCluster(command, log);
    auto evaluator = mrsim::MakeOptEvaluator(
        command, setup, [] { return mrsim::StopRequested(); }, log,
        cluster.get());
    std::unique_ptr<lcm::LCM> progress;  // --progress-url's connection
    const auto publish = mrsim::MakeProgressPublisher(command, &progress);
    const mrsim::OptOutcome outcome = mrsim::RunOpt(
        command, setup, *evaluator, stdout, stderr, cluster.get(), publish);
    // Unfinished: 128 + the signal, as a shell reports it.
    if (outcome.stopped) return 128 + std::max(mrsim::StopSignal(), SIGINT);
    if (!command.replay) return 0;
    evaluator.reset();
    cluster.reset();
    return mrsim::ExecReplay(outcome);
  } catch (const mrsim::UsageError& err) {  // the key file
    fmt::print(stderr, "mrsim-opt: {}\n", err.what());
    return 2;
  } catch (const mrsim::OptInputError& err) {  // flags and files
    fmt::print(stderr, "mrsim-opt: {}\n", err.what());
    return 2;
  } catch (const std::exception& err) {
    fmt::print(stderr, "mrsim-opt: {}\n", err.what());
    return 1;
  }
}

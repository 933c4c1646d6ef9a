// mrsim-worker: evaluates episodes for any mrsim-opt master on the LCM
// network; start any number on any hosts, at any time (docs/optimizer.md).
#include <fmt/format.h>
#include <signal.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/version.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_worker.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-worker: run optimiser episodes for mrsim-opt --farm"};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-worker"));
  std::string lcm_url;
  mrsim::WorkerSettings settings;
  settings.prefix = mrsim::kDefaultFarmPrefix;
  bool quiet = false;
  int fake_workers = 1;
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  app.add_option("--prefix", settings.prefix, "Farm channel prefix")
      ->capture_default_str();
  app.add_option("--id", settings.id, "Worker name (default: host-pid)");
  app.add_option("--threads", settings.threads,
                 "Episodes run at once by this worker")
      ->capture_default_str();
  app.add_flag("--quiet", quiet, "Print nothing but errors");
  app.add_option("--fake-episode", settings.fake_episode,
                 "Protocol-only worker for farm tests: episodes take this "
                 "many s and run no physics");
  app.add_option("--fake-workers", fake_workers,
                 "With --fake-episode: this many workers in this process")
      ->check(CLI::Range(1, 100000));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& err) {
    const int code = app.exit(err);
    return code == 0 ? 0 : 2;
  }
  if (settings.threads < 1) {
    std::cerr << "mrsim-worker: --threads must be >= 1\n";
    return 2;
  }
  if (fake_workers > 1 && settings.fake_episode <= 0) {
    std::cerr << "mrsim-worker: --fake-workers needs --fake-episode\n";
    return 2;
  }
  try {
    mrsim::InstallStopHandlers();
    signal(SIGPIPE, SIG_IGN);  // a tcpq hub that goes away: re-connect
    mrsim::FarmWorker worker(lcm_url, settings, fake_workers);
    if (!quiet) {
      fmt::print("mrsim-worker {}: waiting for a run on {}_*\n", worker.id(),
                 settings.prefix);
      std::fflush(stdout);
    }
    while (!mrsim::StopRequested()) {
      for (const std::string& line : worker.Poll(20)) {
        if (!quiet) fmt::print("mrsim-worker {}: {}\n", worker.id(), line);
      }
      std::fflush(stdout);
    }
    const mrsim::WorkerCounters c = worker.counters();
    if (!quiet) {
      fmt::print(
          "mrsim-worker {}: stopping; {} jobs done, {} heartbeats sent, {} "
          "messages ignored, {} malformed\n",
          worker.id(), c.jobs_done, c.heartbeats_sent, c.messages_ignored,
          c.messages_malformed);
    }
    return 0;
  } catch (const std::exception& err) {
    std::cerr << "mrsim-worker: " << err.what() << "\n";
    return 1;
  }
}

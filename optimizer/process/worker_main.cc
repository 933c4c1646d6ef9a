// mrsim-worker: evaluates episodes for any mrsim-opt master on the LCM
// network; start any number on any hosts, at any time (docs/optimizer.md).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "common/version.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_worker.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-worker: run optimiser episodes for mrsim-opt --farm"};
  app.set_version_flag("--version",
                       std::string("mrsim-worker ") + mrsim::kVersion);
  std::string lcm_url;
  mrsim::WorkerSettings settings;
  settings.prefix = mrsim::kDefaultFarmPrefix;
  bool quiet = false;
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  app.add_option("--prefix", settings.prefix, "Farm channel prefix")
      ->capture_default_str();
  app.add_option("--id", settings.id, "Worker name (default: host-pid)");
  app.add_option("--threads", settings.threads,
                 "Episodes run at once by this worker")
      ->capture_default_str();
  app.add_flag("--quiet", quiet, "Print nothing but errors");
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
  try {
    mrsim::InstallStopHandlers();
    lcm::LCM lcm(lcm_url);
    if (!lcm.good()) {
      std::cerr << "mrsim-worker: cannot open LCM '" << lcm_url
                << "' (no multicast route? see docs/optimizer.md)\n";
      return 1;
    }
    mrsim::FarmWorker worker(lcm, settings);
    if (!quiet) {
      fmt::print("mrsim-worker {}: waiting for a run on {}_*\n", worker.id(),
                 settings.prefix);
      std::fflush(stdout);
    }
    while (!mrsim::StopRequested()) {
      mrsim::HandleFor(lcm, 20);
      for (const std::string& line : worker.Poll()) {
        if (!quiet) fmt::print("mrsim-worker {}: {}\n", worker.id(), line);
      }
      std::fflush(stdout);
    }
    const mrsim::WorkerCounters c = worker.counters();
    if (!quiet) {
      fmt::print(
          "mrsim-worker {}: stopping; {} jobs done, {} messages ignored, {} "
          "malformed\n",
          worker.id(), c.jobs_done, c.messages_ignored, c.messages_malformed);
    }
    return 0;
  } catch (const std::exception& err) {
    std::cerr << "mrsim-worker: " << err.what() << "\n";
    return 1;
  }
}

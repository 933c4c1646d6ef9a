#include "optimizer/process/worker_command.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "common/printable.h"
#include "optimizer/farm/farm_worker.h"

namespace mrsim {

void AddWorkerFlags(CLI::App& app, WorkerCommand& command) {
  WorkerSettings& settings = command.settings;
  app.add_option("--lcm-url", command.lcm_url,
                 "LCM URL (default: LCM's default)");
  AddAuthFlags(app, command.auth);
  app.add_option("--prefix", settings.prefix, "Farm channel prefix")
      ->capture_default_str();
  app.add_option("--id", settings.id, "Worker name (default: host-pid)");
  app.add_option("--threads", settings.threads,
                 "Episodes run at once by this worker")
      ->capture_default_str();
  app.add_flag("--quiet", command.quiet, "Print nothing but errors");
  app.add_option("--fake-episode", settings.fake_episode,
                 "Protocol-only worker for farm tests: episodes take this "
                 "many s and run no physics");
  app.add_option("--fake-workers", command.fake_workers,
                 "With --fake-episode: this many workers in this process")
      ->check(CLI::Range(1, 100000));
  // Hidden: a lying worker for the tests of mrsim-opt --verify.
  app.add_option("--test-lie", settings.lie,
                 "Tests only: add this to every fitness reported")
      ->group("");
}

void CheckWorkerCommand(const WorkerCommand& command) {
  if (command.settings.threads < 1) {
    throw WorkerInputError("--threads must be >= 1");
  }
  if (command.fake_workers > 1 && command.settings.fake_episode <= 0) {
    throw WorkerInputError("--fake-workers needs --fake-episode");
  }
}

void RunWorkerCommand(const WorkerCommand& command, std::FILE* out,
                      const std::function<bool()>& stop) {
  WorkerSettings settings = command.settings;
  settings.auth = command.auth.Load();
  FarmWorker worker(command.lcm_url, settings, command.fake_workers);
  const auto say = [&](const std::string& line) {
    if (command.quiet) return;
    fmt::print(out, "mrsim-worker {}: {}\n", Printable(worker.id()),
               Printable(line));
    std::fflush(out);
  };
  say("waiting for a run on " + command.settings.prefix + "_*");
  while (!stop()) {
    for (const std::string& line : worker.Poll(20)) say(line);
  }
  const WorkerCounters c = worker.counters();
  say(fmt::format(
      "stopping; {} jobs done, {} heartbeats sent, {} messages ignored, {} "
      "malformed",
      c.jobs_done, c.heartbeats_sent, c.messages_ignored,
      c.messages_malformed));
}

}  // namespace mrsim

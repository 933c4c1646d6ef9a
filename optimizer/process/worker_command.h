// mrsim-worker as library code: its flags, the checks of their values, and
// the loop that runs a FarmWorker until asked to stop, printing its log.
// main only parses, installs the signal handlers and calls these.
#pragma once

#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

#include "lcmtypes/runtime/auth_flags.h"
#include "optimizer/farm/farm_worker_core.h"

namespace CLI {
class App;
}

namespace mrsim {

// Everything the command line sets.
struct WorkerCommand {
  std::string lcm_url;  // empty: LCM's default
  AuthFlags auth;
  WorkerSettings settings;
  bool quiet = false;
  int fake_workers = 1;
};

// Registers every flag of mrsim-worker on `app`, writing into `command`.
void AddWorkerFlags(CLI::App& app, WorkerCommand& command);

// A combination of flags that cannot run (mrsim-worker exits with 2).
class WorkerInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws WorkerInputError naming the flag when the values cannot run.
void CheckWorkerCommand(const WorkerCommand& command);

// Joins the farm and works until `stop` returns true (checked every 20 ms),
// printing the worker's lines to `out` unless quiet. Throws what the LCM
// connection or the worker throws.
void RunWorkerCommand(const WorkerCommand& command, std::FILE* out,
                      const std::function<bool()>& stop);

}  // namespace mrsim

// What mrsim-opt --hub and --slurm start around a farm run: LCM's TCP hub
// and one Slurm array job of mrsim-worker tasks. Destroying it cancels
// the array (only this run's job) and then stops the hub, so a run that
// ends, fails or is interrupted leaves no workers queued or running.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "optimizer/slurm/lcm_hub.h"
#include "optimizer/slurm/slurm_array.h"
#include "optimizer/slurm/slurm_runner.h"

namespace mrsim {

struct FarmClusterOptions {
  int hub_port = 0;                        // 0: no hub
  int slurm_tasks = 0;                     // 0: no array
  std::vector<std::string> slurm_options;  // --slurm-opt, as given
  std::string lcm_url;                     // --lcm-url ("" : derived)
  // The farm's default, as its .lcm files declare it.
  std::string prefix = ChannelNamed("run").default_prefix;
  std::string key_file;        // passed on to the workers when set
  std::string worker_program;  // mrsim-worker as the nodes see it
  std::string out_dir;         // hub.log and slurm/ logs go here
  std::string host;            // this host's name, for the workers' URL
  double poll_interval = 2.0;
};

// The URL the workers get: --lcm-url, else tcpq://HOST:PORT with --hub,
// else "" (LCM's default). Throws std::invalid_argument when --hub and a
// --lcm-url that is not tcpq:// on the same port are both given.
std::string WorkerLcmUrl(const FarmClusterOptions& options);

// The shell command of each array task (sbatch --wrap): mrsim-worker with
// the run's URL and prefix, as many episode threads as Slurm gave the
// task CPUs.
std::string WorkerCommandLine(const FarmClusterOptions& options);

class FarmCluster {
 public:
  // Starts the hub, then submits the array (each when asked for). Throws
  // std::runtime_error / SlurmError; what was started is stopped again.
  FarmCluster(const FarmClusterOptions& options,
              std::unique_ptr<SlurmRunner> runner,
              const std::function<void(const std::string&)>& log);
  ~FarmCluster();
  FarmCluster(const FarmCluster&) = delete;
  FarmCluster& operator=(const FarmCluster&) = delete;

  // What this process connects to: the hub on loopback, or --lcm-url.
  const std::string& master_url() const { return master_url_; }
  // " | slurm 42: 3 running, 1 pending" (squeue at most every poll
  // interval), "" without an array.
  std::string ProgressNote();
  SlurmArray* array() { return array_.get(); }

  // Cancels the array now (the destructor does it too).
  void CancelWorkers();

 private:
  std::unique_ptr<SlurmRunner> runner_;
  std::unique_ptr<LcmHub> hub_;
  std::unique_ptr<SlurmArray> array_;
  std::string master_url_;
  std::function<void(const std::string&)> log_;
};

}  // namespace mrsim

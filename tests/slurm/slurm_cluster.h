// A real Slurm cluster on this host for tests: munged, slurmctld and N
// slurmd (nodes n1..nN on 127.0.0.1, one CPU each), all under one folder
// with their own ports, socket, key, state and pid files; client commands
// find it through $SLURM_CONF. Needs root and Debian's slurm-wlm and munge
// (scripts/install_deps.sh). Destroying it cancels every job of the cluster
// and stops each daemon by its pid file (never by name); daemons a crashed
// run left in the same folder are stopped the same way before starting.
#pragma once

#include <string>
#include <vector>

#include "common/command_output.h"

namespace mrsim::testing {

class SlurmCluster {
 public:
  // False (and why) when this host cannot run one: not root, or a program
  // missing.
  static bool Available(std::string* why);

  // Starts the daemons in /tmp/mrsim-slurm-PORT (their unix sockets need
  // a short path), slurmctld on `port`, the nodes' slurmd on
  // port+1..port+nodes, and waits until every node is idle.
  // Sets SLURM_CONF for this process and its children. Throws
  // std::runtime_error with the daemons' logs when it does not come up.
  explicit SlurmCluster(int port, int nodes = 4);
  ~SlurmCluster();
  SlurmCluster(const SlurmCluster&) = delete;
  SlurmCluster& operator=(const SlurmCluster&) = delete;

  const std::string& conf() const { return conf_; }
  const std::string& dir() const { return dir_; }
  // Runs a Slurm client command ("squeue", "scancel" ...) on this cluster.
  CommandOutput Run(const std::vector<std::string>& argv) const;
  // The tasks squeue lists for `job` ("42_0 RUNNING" lines; COMPLETING
  // ones included), "" once it left the queue.
  std::string Tasks(const std::string& job) const;
  // What the daemons logged, for a failure message.
  std::string Logs() const;

 private:
  void StopAll();
  std::string dir_;
  std::string conf_;
  std::vector<std::string> pid_files_;  // munged last
};

}  // namespace mrsim::testing

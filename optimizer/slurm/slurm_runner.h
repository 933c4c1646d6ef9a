// How SlurmArray talks to the scheduler: one call per sbatch, squeue or
// scancel. The real one starts the programs (ProcessSlurmRunner); tests
// give a fake that answers as a cluster would, with no scheduler around.
#pragma once

#include <string>
#include <vector>

#include "common/command_output.h"

namespace mrsim {

class SlurmRunner {
 public:
  virtual ~SlurmRunner() = default;
  // Runs argv ("sbatch", "squeue" or "scancel" and its arguments) and
  // returns its exit code and output. Throws std::runtime_error when the
  // program cannot be started at all.
  virtual CommandOutput Run(const std::vector<std::string>& argv) = 0;
};

// Starts the Slurm client programs found on $PATH (they read $SLURM_CONF
// like any Slurm command), each with a deadline.
class ProcessSlurmRunner : public SlurmRunner {
 public:
  explicit ProcessSlurmRunner(double timeout_s = 30.0)
      : timeout_s_(timeout_s) {}
  CommandOutput Run(const std::vector<std::string>& argv) override {
    return RunForOutput(argv, timeout_s_);
  }

 private:
  double timeout_s_;
};

}  // namespace mrsim

// One Slurm array job of farm workers, as a driver (Ray, Dask-jobqueue)
// keeps its own: submitted with `sbatch --parsable --array=0-(N-1)`,
// watched with squeue (how many tasks wait and how many run, for the
// progress line) and cancelled with `scancel JOBID` when the run ends,
// that job and no other. Plain logic: the scheduler is reached through a
// SlurmRunner and time is passed in, so tests use a fake of both.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "optimizer/slurm/slurm_runner.h"

namespace mrsim {

// The scheduler refused or could not be reached (sbatch failed, an answer
// that is no job id), or an sbatch option that cannot be passed.
class SlurmError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SlurmArraySettings {
  int tasks = 1;                     // array tasks, one worker each
  std::vector<std::string> options;  // sbatch options, "--name=value"
  std::string job_name = "mrsim-worker";
  std::string command;         // shell command each task runs (sbatch --wrap)
  std::string output;          // sbatch --output pattern; "" for Slurm's
  double poll_interval = 5.0;  // s between two squeue calls at most
};

// The array's tasks by state, as squeue last listed them.
struct SlurmCounts {
  bool known = false;  // squeue answered at least once
  int pending = 0;     // waiting for a node (PENDING, REQUEUED, ...)
  int running = 0;     // RUNNING or CONFIGURING
  int other = 0;       // suspended, completing, ...
};

// "partition=debug" -> "--partition=debug"; "-p debug" style short options
// are taken as they are. Throws SlurmError for an empty option and for
// those the array sets itself (--array, --parsable, --wrap, --output,
// --job-name is allowed).
std::string NormaliseSbatchOption(const std::string& option);

// Counts squeue's "%i %T" lines ("42_3 RUNNING", "42_[4-7%2] PENDING").
// Lines it cannot read are skipped.
SlurmCounts ParseSqueue(const std::string& output);

class SlurmArray {
 public:
  SlurmArray(SlurmRunner& runner, SlurmArraySettings settings);
  // Cancels the job (once) if it was submitted; never throws.
  ~SlurmArray();
  SlurmArray(const SlurmArray&) = delete;
  SlurmArray& operator=(const SlurmArray&) = delete;

  // The sbatch command line Submit runs.
  std::vector<std::string> SubmitCommand() const;
  // Submits the array; throws SlurmError with sbatch's own words.
  void Submit();
  const std::string& job_id() const { return job_id_; }

  // Asks squeue when poll_interval has passed since the last call (or at
  // the first); returns true when it asked. A failing squeue keeps the
  // last counts and says so in Describe().
  bool Poll(double now);
  const SlurmCounts& counts() const { return counts_; }
  // "slurm 42: 3 running, 1 pending" (what the progress line shows).
  std::string Describe() const;

  // scancel JOBID, once; true when scancel succeeded (or nothing to do).
  bool Cancel();
  bool cancelled() const { return cancelled_; }
  const std::string& last_error() const { return last_error_; }

 private:
  SlurmRunner& runner_;
  SlurmArraySettings settings_;
  std::string job_id_;
  SlurmCounts counts_;
  double last_poll_ = 0.0;
  bool polled_ = false;
  bool cancelled_ = false;
  std::string last_error_;
};

}  // namespace mrsim

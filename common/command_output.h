// Runs a short-lived program to its end and keeps what it printed: for
// programs whose answer is their output (a scheduler's sbatch, squeue,
// scancel). Built on Subprocess, so a program that hangs is killed at the
// deadline and none is left behind.
#pragma once

#include <string>
#include <vector>

namespace mrsim {

struct CommandOutput {
  int exit_code = -1;  // as Subprocess::Wait: 128+signal when killed
  std::string output;  // stdout and stderr together, at most kMaxOutput
  bool timed_out = false;

  static constexpr std::size_t kMaxOutput = 4 << 20;
};

// Starts argv (argv[0] a path, or a name found on $PATH) and waits up to
// timeout_s for it to end. Throws std::runtime_error when it cannot start.
CommandOutput RunForOutput(const std::vector<std::string>& argv,
                           double timeout_s);

// The path of `program` on $PATH (or `program` itself when it holds a
// slash and exists); "" when there is none.
std::string FindOnPath(const std::string& program);

}  // namespace mrsim

// A real child process for multi-process tests (a common/subprocess.h
// Subprocess): its output captured to a file, stopped with a signal, reaped
// on destruction so no test leaves a process behind.
#pragma once

#include <sys/types.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "common/subprocess.h"

namespace mrsim::testing {

class ChildProcess {
 public:
  // Starts argv[0] (a path) with the given arguments; stdout and stderr go
  // to `log_path` (or /dev/null when empty).
  ChildProcess(const std::vector<std::string>& argv,
               const std::string& log_path = "");
  // Stops it with SIGTERM (SIGKILL after 2 s) so it can flush.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return process_.pid(); }
  bool running() { return process_.running(); }
  void Signal(int sig) { process_.Signal(sig); }
  // Waits up to timeout_s for exit; returns the exit code, 128+signal when
  // killed by a signal, or -1 on timeout.
  int Wait(double timeout_s) { return process_.Wait(timeout_s); }
  // SIGTERM, then SIGKILL after grace_s. Returns as Wait.
  int Stop(double grace_s = 5.0) { return process_.Stop(grace_s); }
  // What it printed so far (empty without a log file).
  std::string Output() const;
  // Waits until the output holds `text` (true), the process ended without
  // printing it, or timeout_s passed (false).
  bool WaitForOutput(const std::string& text, double timeout_s);

 private:
  std::string log_path_;
  Subprocess process_;
};

// A multicast URL on loopback with its own port and ttl=0, so concurrent
// tests never hear each other. MRSIM_TEST_PORT_OFFSET shifts every port, so
// two checkouts can run their suites on one host at once (Linux delivers a
// multicast datagram to every socket bound to its port, whatever the group).
inline std::string TestLcmUrl(int port) {
  const char* offset = std::getenv("MRSIM_TEST_PORT_OFFSET");
  if (offset != nullptr) port += std::atoi(offset);
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
}

// Path of a built program, e.g. BinaryPath("sim_core/sim_process/mrsim-sim").
std::string BinaryPath(const std::string& relative);
// Path of a file in the source tree, e.g. SourcePath("scenarios/snake.xml").
std::string SourcePath(const std::string& relative);
// A fresh empty directory under the build tree for one test.
std::string TempDir(const std::string& name);

}  // namespace mrsim::testing

// A child process started with posix_spawn: its stdout and stderr go
// together to the parent's, a file, /dev/null or a pipe the parent reads;
// stdin is /dev/null. Waiting has a deadline and no sleep (a pidfd is
// polled). A Subprocess still running when destroyed is killed and reaped,
// so no caller leaves a process behind.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace mrsim {

struct SpawnOptions {
  enum class Output { kInherit, kNull, kFile, kPipe };
  Output output = Output::kInherit;
  std::string output_path;  // for kFile (created or truncated)
  std::string working_dir;  // empty: the parent's
  // In a process group of its own: the terminal's Ctrl-C (sent to the
  // foreground group) does not reach it, so the parent decides when it
  // stops (a hub its siblings need until they have stopped).
  bool own_process_group = false;

  // Output to a file (created or truncated).
  static SpawnOptions ToFile(const std::string& path) {
    SpawnOptions options;
    options.output = Output::kFile;
    options.output_path = path;
    return options;
  }
};

class Subprocess {
 public:
  // Starts argv[0], a path (no PATH search). Throws std::runtime_error
  // "cannot start PROGRAM: REASON".
  explicit Subprocess(const std::vector<std::string>& argv,
                      const SpawnOptions& options = {});
  ~Subprocess();
  Subprocess(const Subprocess&) = delete;
  Subprocess& operator=(const Subprocess&) = delete;

  pid_t pid() const { return pid_; }
  // The read end of the output pipe (non-blocking) for kPipe, else -1.
  // Closed by the Subprocess.
  int output_fd() const { return out_fd_; }
  void CloseOutput();

  // False once the process ended (it is reaped then).
  bool running();
  void Signal(int sig);
  // Waits up to timeout_s for the exit; returns the exit code, 128+signal
  // when killed by a signal, or -1 on timeout.
  int Wait(double timeout_s);
  // SIGTERM, then SIGKILL after grace_s. Returns as Wait.
  int Stop(double grace_s = 5.0);
  // The waitpid status once ended.
  int status() const { return status_; }
  // CPU seconds (user + system, every thread) it used; once ended.
  double cpu_seconds() const { return cpu_seconds_; }

 private:
  int ExitCode() const;
  pid_t pid_ = -1;
  int pid_fd_ = -1;
  int out_fd_ = -1;
  int status_ = 0;
  double cpu_seconds_ = 0.0;
  bool reaped_ = false;
};

// "exited with code N" or "killed by signal NAME", from a waitpid status.
std::string DescribeExitStatus(int status);

}  // namespace mrsim

// The processes of one launch: starts them, forwards their output line by
// line prefixed with their names, notices when one exits and stops them all.
#pragma once

#include <sys/types.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "common/subprocess.h"
#include "launcher/launch_file.h"

namespace mrsim {

class ProcessGroup {
 public:
  // Output goes to `out` (stdout in the launcher); colours when it is a tty.
  explicit ProcessGroup(std::FILE* out);
  // Each whole line goes to `sink` with the name of the process that wrote
  // it ("launch" for the group's own), e.g. a console panel in a window.
  using LineSink =
      std::function<void(const std::string& name, const std::string& line)>;
  explicit ProcessGroup(LineSink sink);
  ~ProcessGroup();
  ProcessGroup(const ProcessGroup&) = delete;
  ProcessGroup& operator=(const ProcessGroup&) = delete;

  // Starts `spec` running `program_path`. Throws std::runtime_error when the
  // program cannot be started.
  void Start(const ProcessSpec& spec, const std::string& program_path);

  // Forwards output for up to timeout_ms and reaps processes that ended.
  // Returns the name of a required process that exited, or "".
  std::string Poll(int timeout_ms);

  // SIGINT to all that run, then SIGTERM after grace_s, then SIGKILL;
  // forwards their last output. Returns when every process has ended.
  // Hubs (ProcessSpec::stop_last) only once every other process ended.
  void StopAll(double grace_s);

  // Stops the running processes whose spec `which` picks, as StopAll does
  // (hubs among them only if picked).
  using Which = std::function<bool(const ProcessSpec&)>;
  void Stop(const Which& which, double grace_s);

  // True once the process `name` has printed a line its
  // ProcessSpec::ready_line finds (or at once when it has none).
  bool IsReady(const std::string& name) const;

  bool AnyRunning() const;
  bool AnyRunning(const Which& which) const;
  // True when every process ended with exit code 0, or was stopped: ended
  // by SIGINT or SIGTERM, or exited 128 + that signal (mrsim-opt does when
  // it leaves a run unfinished), after StopAll signalled it or, with
  // `interrupted`, after the user's Ctrl-C reached the whole group.
  bool AllClean(bool interrupted = false) const;
  // One line per process: name, how it ended.
  std::string Summary() const;
  // Prints a line prefixed with the launcher's own name.
  void Say(const std::string& line);
  // Makes the name column at least as wide as `name`, so the lines before
  // a process with a long name starts line up with those after.
  void FitName(const std::string& name) {
    name_width_ = std::max(name_width_, name.size());
  }

 private:
  struct Child {
    ProcessSpec spec;
    std::unique_ptr<Subprocess> process;  // output on a non-blocking pipe
    std::string pending;                  // partial line not yet printed
    bool running = false;
    int status = 0;
    bool stopped_by_us = false;
    int colour = 0;
    std::shared_ptr<const std::regex> ready_line;  // null: none, or seen
  };
  // Signals the running children `which` picks, escalating.
  void StopStage(const Which& which, double grace_s);
  void Forward(Child& child, bool flush_partial);
  void Reap(Child& child, int status);
  void PrintLine(Child& child, const std::string& line);

  std::FILE* out_ = nullptr;
  LineSink sink_;
  bool colour_ = false;
  size_t name_width_ = 6;
  std::vector<Child> children_;
};

}  // namespace mrsim

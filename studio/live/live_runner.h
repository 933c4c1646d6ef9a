// What the studio's Run and Record buttons start: mrsim-sim and one
// mrsim-gait (or mrsim-lua) per robot for the current design, or the
// simulator alone waiting for an external controller, and mrsim-log into a
// folder, as ordinary child processes (the launcher's ProcessGroup), their
// output kept for the console panel. Every command line is one a user could
// type.
#pragma once

#include <cstdint>
#include <ctime>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "launcher/launch_file.h"
#include "launcher/process_group.h"
#include "launcher/run_options.h"

namespace mrsim::studio {

// A CSV the recording wrote, with its data rows (header excluded).
struct RecordedFile {
  std::string path;
  int64_t rows = 0;
};

class LiveRunner {
 public:
  // Programs are looked up on `search_path` (ProgramSearchPath(argv0)).
  explicit LiveRunner(std::vector<std::string> search_path);
  ~LiveRunner();
  LiveRunner(const LiveRunner&) = delete;
  LiveRunner& operator=(const LiveRunner&) = delete;

  // The processes Start runs (RunProcessSpecs, as `mrsim run` starts
  // them), in start order: the gait nodes first so they hear the first
  // state. Throws std::invalid_argument for options that no run could use.
  static std::vector<ProcessSpec> RunSpecs(const RunOptions& options);
  static ProcessSpec RecordSpec(const RunOptions& options,
                                const std::string& out_dir);

  // Stops what runs, then starts a run. Throws std::runtime_error naming
  // the program that could not be found or started.
  void Start(const RunOptions& options);
  // Ends the run (and a recording) cleanly: SIGINT, then harder.
  void Stop();
  bool running() const;

  // Records every channel of the run into out_dir (see
  // NewRecordingFolder for a folder of its own per recording).
  void StartRecording(const std::string& out_dir);
  void StopRecording();
  bool recording() const;
  const std::string& record_dir() const { return record_dir_; }
  // The CSVs in the recording folder with their row counts.
  std::vector<RecordedFile> RecordedFiles() const;

  // Takes the children's output and notices exits; call once per frame.
  void Poll();
  // "[sim] ..." lines, the newest last (at most kConsoleLines).
  const std::deque<std::string>& console() const { return console_; }
  static constexpr size_t kConsoleLines = 2000;

 private:
  void Line(const std::string& name, const std::string& line);
  std::string Find(const std::string& program) const;

  std::vector<std::string> search_path_;
  RunOptions options_;
  std::unique_ptr<ProcessGroup> run_;
  std::unique_ptr<ProcessGroup> record_;
  std::string record_dir_;
  std::deque<std::string> console_;
};

// A folder of its own for one recording under `base`, named by the local
// time it starts ("base/2026-11-26_14-05-09", then "..._2" if taken), so
// a new recording never overwrites the last. Nothing is created.
std::string NewRecordingFolder(const std::string& base, std::time_t now);

}  // namespace mrsim::studio

#include "studio/live/live_runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "launcher/program_locator.h"

namespace mrsim::studio {
namespace {

int64_t DataRows(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  int64_t lines = 0;
  char buf[1 << 16];
  while (in.read(buf, sizeof(buf)) || in.gcount() > 0) {
    lines += std::count(buf, buf + in.gcount(), '\n');
  }
  return std::max<int64_t>(0, lines - 1);  // the header
}

}  // namespace

LiveRunner::LiveRunner(std::vector<std::string> search_path)
    : search_path_(std::move(search_path)) {}

LiveRunner::~LiveRunner() { Stop(); }

std::vector<ProcessSpec> LiveRunner::RunSpecs(const RunOptions& o) {
  return RunProcessSpecs(o);
}

ProcessSpec LiveRunner::RecordSpec(const RunOptions& o,
                                   const std::string& out_dir) {
  if (out_dir.empty()) throw std::invalid_argument("record: no folder");
  ProcessSpec log;
  log.name = "log";
  log.program = "mrsim-log";
  log.args = {"--out", out_dir};
  const auto lcm = RunLcmArgs(o);
  log.args.insert(log.args.end(), lcm.begin(), lcm.end());
  return log;
}

std::string LiveRunner::Find(const std::string& program) const {
  return FindProgram(program, search_path_);
}

void LiveRunner::Line(const std::string& name, const std::string& line) {
  console_.push_back("[" + name + "] " + line);
  while (console_.size() > kConsoleLines) console_.pop_front();
}

void LiveRunner::Start(const RunOptions& options) {
  Stop();
  const std::vector<ProcessSpec> specs = RunSpecs(options);
  options_ = options;
  run_ = std::make_unique<ProcessGroup>(
      [this](const std::string& name, const std::string& line) {
        Line(name, line);
      });
  for (const ProcessSpec& spec : specs) run_->Start(spec, Find(spec.program));
}

void LiveRunner::Stop() {
  StopRecording();
  if (run_) {
    run_->StopAll(3.0);
    run_.reset();
  }
}

bool LiveRunner::running() const { return run_ && run_->AnyRunning(); }

void LiveRunner::StartRecording(const std::string& out_dir) {
  StopRecording();
  const ProcessSpec spec = RecordSpec(options_, out_dir);
  record_ = std::make_unique<ProcessGroup>(
      [this](const std::string& name, const std::string& line) {
        Line(name, line);
      });
  record_dir_ = out_dir;
  record_->Start(spec, Find(spec.program));
}

void LiveRunner::StopRecording() {
  if (record_) {
    record_->StopAll(5.0);  // mrsim-log flushes its CSVs on SIGINT
    record_.reset();
  }
}

bool LiveRunner::recording() const { return record_ && record_->AnyRunning(); }

std::vector<RecordedFile> LiveRunner::RecordedFiles() const {
  std::vector<RecordedFile> files;
  std::error_code ec;
  if (record_dir_.empty()) return files;
  for (const auto& entry :
       std::filesystem::directory_iterator(record_dir_, ec)) {
    if (entry.path().extension() != ".csv") continue;
    files.push_back({entry.path().string(), DataRows(entry.path().string())});
  }
  std::sort(files.begin(), files.end(),
            [](const RecordedFile& a, const RecordedFile& b) {
              return a.path < b.path;
            });
  return files;
}

void LiveRunner::Poll() {
  if (run_) run_->Poll(0);
  if (record_) record_->Poll(0);
}

std::string NewRecordingFolder(const std::string& base, std::time_t now) {
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y-%m-%d_%H-%M-%S", &local);
  const std::string first = (base.empty() ? "." : base) + "/" + stamp;
  std::string folder = first;
  for (int k = 2; std::filesystem::exists(folder); ++k) {
    folder = first + "_" + std::to_string(k);
  }
  return folder;
}

}  // namespace mrsim::studio

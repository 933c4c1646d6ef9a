#include "tests/common/child_process.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace mrsim::testing {

namespace {

SpawnOptions LogTo(const std::string& log_path) {
  SpawnOptions options;
  options.output = log_path.empty() ? SpawnOptions::Output::kNull
                                    : SpawnOptions::Output::kFile;
  options.output_path = log_path;
  return options;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv,
                           const std::string& log_path)
    : log_path_(log_path), process_(argv, LogTo(log_path)) {}

ChildProcess::~ChildProcess() { process_.Stop(2.0); }

std::string ChildProcess::Output() const {
  if (log_path_.empty()) return "";
  std::ifstream in(log_path_);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool ChildProcess::WaitForOutput(const std::string& text, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (Output().find(text) != std::string::npos) return true;
    if (!running()) return Output().find(text) != std::string::npos;
    // Polls the log file: a check every 20 ms, the deadline decides.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

std::string BinaryPath(const std::string& relative) {
  return std::string(MRSIM_BINARY_DIR) + "/" + relative;
}

std::string SourcePath(const std::string& relative) {
  return std::string(MRSIM_SOURCE_DIR) + "/" + relative;
}

std::string TempDir(const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(MRSIM_BINARY_DIR) / "test_tmp" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

}  // namespace mrsim::testing

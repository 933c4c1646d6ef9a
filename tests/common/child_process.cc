#include "tests/common/child_process.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/common/wait_until.h"

namespace mrsim::testing {

namespace {

SpawnOptions LogTo(const std::string& log_path) {
  if (!log_path.empty()) return SpawnOptions::ToFile(log_path);
  SpawnOptions options;
  options.output = SpawnOptions::Output::kNull;
  return options;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv,
                           const std::string& log_path)
    : log_path_(log_path), process_(argv, LogTo(log_path)) {}

ChildProcess::~ChildProcess() { process_.Stop(2.0); }

std::string ChildProcess::Output() const {
  return log_path_.empty() ? "" : ReadFileText(log_path_);
}

bool ChildProcess::WaitForOutput(const std::string& text, double timeout_s) {
  // Ends early when the process does: what it printed is all there is.
  WaitUntil(
      [&] { return !running() || Output().find(text) != std::string::npos; },
      timeout_s);
  return Output().find(text) != std::string::npos;
}

std::string BinaryPath(const std::string& relative) {
  return std::string(MRSIM_BINARY_DIR) + "/" + relative;
}

std::string SourcePath(const std::string& relative) {
  return std::string(MRSIM_SOURCE_DIR) + "/" + relative;
}

std::string TempDir(const std::string& name) {
  namespace fs = std::filesystem;
  // ctest runs each test of a file as its own process, in parallel: a
  // folder per test keeps one test from clearing another's files.
  const ::testing::TestInfo* test =
      ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string owner =
      test ? std::string(test->test_suite_name()) + "." + test->name()
           : "pid" + std::to_string(::getpid());
  const fs::path dir = fs::path(MRSIM_BINARY_DIR) / "test_tmp" / name / owner;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

}  // namespace mrsim::testing

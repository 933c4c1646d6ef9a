#include "common/subprocess.h"

#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Subprocess, ReportsExitCodeAndSignal) {
  SpawnOptions quiet;
  quiet.output = SpawnOptions::Output::kNull;
  Subprocess ok({"/bin/sh", "-c", "exit 3"}, quiet);
  EXPECT_EQ(ok.Wait(30), 3);
  EXPECT_FALSE(ok.running());
  EXPECT_EQ(DescribeExitStatus(ok.status()), "exited with code 3");
  // stdin is /dev/null: a read ends at once (1: end of input).
  Subprocess reads({"/bin/sh", "-c", "read x"});
  EXPECT_EQ(reads.Wait(30), 1);
  Subprocess sleeper({"/bin/sleep", "60"});
  sleeper.Signal(SIGTERM);
  EXPECT_EQ(sleeper.Wait(30), 128 + SIGTERM);
}

TEST(Subprocess, WaitTimesOutAndStopEscalates) {
  // Ignores SIGTERM, so Stop needs SIGKILL; it says so once the trap is
  // set (a child slow to start would otherwise die of the SIGTERM).
  SpawnOptions options;
  options.output = SpawnOptions::Output::kPipe;
  Subprocess stubborn(
      {"/bin/sh", "-c", "trap '' TERM; echo ready; while :; do :; done"},
      options);
  std::string said;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (said.find("ready") == std::string::npos &&
         std::chrono::steady_clock::now() < end) {
    pollfd fd{stubborn.output_fd(), POLLIN, 0};
    poll(&fd, 1, 1000);
    char buffer[64];
    const ssize_t n = read(stubborn.output_fd(), buffer, sizeof(buffer));
    if (n > 0) said.append(buffer, static_cast<size_t>(n));
  }
  ASSERT_NE(said.find("ready"), std::string::npos);
  EXPECT_EQ(stubborn.Wait(0.05), -1);
  EXPECT_EQ(stubborn.Stop(0.2), 128 + SIGKILL);
}

TEST(Subprocess, OutputToAFileInAWorkingDirectory) {
  const std::string dir = testing::TempDir("subprocess_file");
  SpawnOptions options;
  options.output = SpawnOptions::Output::kFile;
  options.output_path = dir + "/log.txt";
  options.working_dir = dir;
  Subprocess p({"/bin/sh", "-c", "pwd; echo err >&2"}, options);
  ASSERT_EQ(p.Wait(30), 0);
  EXPECT_EQ(ReadAll(dir + "/log.txt"),
            std::filesystem::canonical(dir).string() + "\nerr\n");
}

TEST(Subprocess, PipeNeverBlocksTheReader) {
  // 8 KB, then silence: a blocking reader would hang on the third read.
  SpawnOptions options;
  options.output = SpawnOptions::Output::kPipe;
  Subprocess p({"/bin/sh", "-c", "head -c 8192 /dev/zero; exec sleep 60"},
               options);
  size_t total = 0;
  char buffer[4096];
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (total < 8192 && std::chrono::steady_clock::now() < end) {
    pollfd fd{p.output_fd(), POLLIN, 0};
    poll(&fd, 1, 1000);
    const ssize_t n = read(p.output_fd(), buffer, sizeof(buffer));
    if (n > 0) total += static_cast<size_t>(n);
  }
  EXPECT_EQ(total, 8192u);
  EXPECT_EQ(read(p.output_fd(), buffer, sizeof(buffer)), -1);
  EXPECT_EQ(errno, EAGAIN);
  EXPECT_TRUE(p.running());
}

TEST(Subprocess, DestructorKillsAndReaps) {
  pid_t pid = -1;
  {
    Subprocess p({"/bin/sleep", "60"});
    pid = p.pid();
    ASSERT_EQ(kill(pid, 0), 0);
  }
  EXPECT_EQ(kill(pid, 0), -1);  // gone, and no zombie left
  EXPECT_EQ(errno, ESRCH);
}

TEST(Subprocess, CpuSecondsIsWhatTheChildSpent) {
  // The CPU time of the child, not of its wall time or of this process.
  Subprocess busy(
      {"/bin/sh", "-c", "i=0; while [ $i -lt 300000 ]; do i=$((i+1)); done"});
  ASSERT_EQ(busy.Wait(60), 0);
  // A second of wall time at next to no CPU (starting a program costs a
  // little, more when a sanitizer run preloads a library into it).
  Subprocess idle({"/bin/sleep", "1"});
  ASSERT_EQ(idle.Wait(60), 0);
  EXPECT_GT(busy.cpu_seconds(), 0.05);
  EXPECT_LT(idle.cpu_seconds(), 0.5);
}

TEST(Subprocess, MissingProgramIsNamed) {
  try {
    Subprocess p({"/no/such/program"});
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/program"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace mrsim

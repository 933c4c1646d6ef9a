// mrsim-worker's library: flags, their checks, and the run loop on an
// in-process LCM (memq://): no sockets, no child process.
#include "optimizer/process/worker_command.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace mrsim {
namespace {

WorkerCommand Parse(std::vector<std::string> args) {
  CLI::App app;
  WorkerCommand command;
  AddWorkerFlags(app, command);
  std::reverse(args.begin(), args.end());
  app.parse(args);
  return command;
}

// What RunWorkerCommand printed.
std::string RunFor(const WorkerCommand& command, int polls) {
  std::FILE* out = std::tmpfile();
  int left = polls;
  RunWorkerCommand(command, out, [&] { return left-- <= 0; });
  std::rewind(out);
  std::string text;
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, out)) > 0) {
    text.append(buffer, n);
  }
  std::fclose(out);
  return text;
}

TEST(WorkerCommand, FlagsFillTheSettings) {
  const WorkerCommand c = Parse(
      {"--prefix", "FARM", "--id", "w1", "--threads", "3", "--quiet",
       "--fake-episode", "0.5", "--fake-workers", "4", "--lcm-url", "memq://"});
  EXPECT_EQ(c.settings.prefix, "FARM");
  EXPECT_EQ(c.settings.id, "w1");
  EXPECT_EQ(c.settings.threads, 3);
  EXPECT_TRUE(c.quiet);
  EXPECT_EQ(c.settings.fake_episode, 0.5);
  EXPECT_EQ(c.fake_workers, 4);
  EXPECT_EQ(c.lcm_url, "memq://");
  EXPECT_NO_THROW(CheckWorkerCommand(c));
  EXPECT_EQ(Parse({}).settings.prefix, "MRSIM_OPT");
}

TEST(WorkerCommand, ValuesThatCannotRunNameTheirFlag) {
  try {
    CheckWorkerCommand(Parse({"--threads", "0"}));
    FAIL() << "no error";
  } catch (const WorkerInputError& e) {
    EXPECT_NE(std::string(e.what()).find("--threads"), std::string::npos);
  }
  try {
    CheckWorkerCommand(Parse({"--fake-workers", "3"}));
    FAIL() << "no error";
  } catch (const WorkerInputError& e) {
    EXPECT_NE(std::string(e.what()).find("--fake-episode"), std::string::npos);
  }
  EXPECT_THROW(Parse({"--fake-workers", "0"}), CLI::ValidationError);
}

TEST(WorkerCommand, SaysWhereItWaitsAndWhatItDidWhenStopped) {
  WorkerCommand c = Parse({"--lcm-url", "memq://", "--id", "tester"});
  const std::string out = RunFor(c, 3);
  EXPECT_NE(out.find("mrsim-worker tester: waiting for a run on MRSIM_OPT_*"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("mrsim-worker tester: stopping; 0 jobs done, "),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("heartbeats sent, 0 messages ignored, 0 malformed"),
            std::string::npos)
      << out;
  c.quiet = true;
  EXPECT_EQ(RunFor(c, 1), "");
}

}  // namespace
}  // namespace mrsim

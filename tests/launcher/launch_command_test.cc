// `mrsim launch`'s work in process: the plan made from a launch file and
// the flags, and running it (launcher_process_test.cc runs the program).
#include "launcher/launch_command.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "launcher/program_locator.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

std::string WriteFile(const std::string& name, const std::string& text) {
  static const std::string dir = testing::TempDir("launch_command");
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

const char kTwo[] = R"(<launch name="two">
  <process name="first" program="/bin/sh" required="true" args="-c 'exit 0'"/>
  <process name="second" program="/bin/echo" args="30 'a b'"/>
</launch>)";

std::string ErrorOf(const LaunchCommand& command) {
  try {
    PlanLaunch("mrsim", command);
  } catch (const LaunchError& e) {
    return e.what();
  }
  return "";
}

TEST(LaunchCommand, PlanFindsEveryProgramAndPrintsLinesAShellReadsBack) {
  LaunchCommand command;
  command.file = WriteFile("two.launch", kTwo);
  const LaunchPlan plan = PlanLaunch("mrsim", command);
  EXPECT_EQ(plan.name, "two");
  ASSERT_EQ(plan.processes.size(), 2u);
  EXPECT_EQ(plan.processes[1].second, "/bin/echo");
  std::ostringstream out;
  PrintPlan(plan, out);
  EXPECT_EQ(out.str(),
            "first (required): /bin/sh -c 'exit 0'\n"
            "second: /bin/echo 30 'a b'\n");
}

TEST(LaunchCommand, BadInputNamesTheFlagOrTheFileAndLine) {
  LaunchCommand command;
  command.file = WriteFile("typo.launch", R"(<launch name="t">
  <process name="ok" program="/bin/true"/>
  <process name="typo" program="mrsim-no-such-program"/>
</launch>)");
  EXPECT_THAT(ErrorOf(command),
              HasSubstr(command.file + ":3: process 'typo': "));
  command.file = WriteFile("two.launch", kTwo);
  command.sets = {"=4"};
  EXPECT_THAT(ErrorOf(command), HasSubstr("--set =4: expected NAME=VALUE"));
  command.sets = {};
  command.without = {"third"};
  EXPECT_THAT(ErrorOf(command),
              HasSubstr("--without third: no process of that name"));
  command.without = {"first", "second"};
  EXPECT_THAT(ErrorOf(command), HasSubstr("every process is left out"));
}

TEST(LaunchCommand, AnUnknownToolIsBadInputNamingIt) {
  try {
    ExecTool("mrsim", "no-such-tool", {});
    FAIL() << "ExecTool returned";
  } catch (const LaunchError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no tool 'no-such-tool': cannot find "
                                    "program 'mrsim-no-such-tool'"));
  }
  // The subcommand mistyped is pointed to, not the list of tools.
  try {
    ExecTool("mrsim", "lanch", {});
    FAIL() << "ExecTool returned";
  } catch (const LaunchError& e) {
    EXPECT_EQ(std::string(e.what()),
              "no tool 'lanch' (did you mean 'mrsim launch FILE'?)");
  }
}

TEST(ProgramLocator, AMistypedProgramNamesTheNearestAndTheOthers) {
  const std::string dir = testing::TempDir("program_locator");
  for (const char* name : {"mrsim-gait", "mrsim-sim", "other"}) {
    const std::string path = dir + "/" + name;
    std::ofstream(path) << "#!/bin/sh\n";
    std::filesystem::permissions(path, std::filesystem::perms::owner_all);
  }
  EXPECT_EQ(ListTools({dir}), (std::vector<std::string>{"gait", "sim"}));
  EXPECT_EQ(FindProgram("mrsim-gait", {dir}), dir + "/mrsim-gait");
  try {
    FindProgram("mrsim-gaitt", {dir});
    FAIL() << "found a program that is not there";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot find program 'mrsim-gaitt' (did you mean "
              "'mrsim-gait'?); the mrsim programs are mrsim-{gait, sim}");
  }
}

// Installed, `mrsim launch demo.launch` finds the bundled file from any
// folder; a path, or a file in the current folder, is taken as given.
TEST(LaunchCommand, ABareNameFindsABundledLaunchFile) {
  const std::string data = testing::TempDir("launch_data_dir");
  std::filesystem::create_directories(data + "/launch");
  std::ofstream(data + "/launch/bundled.launch") << kTwo;
  setenv("MRSIM_DATA_DIR", data.c_str(), 1);
  EXPECT_EQ(FindLaunchFile("bundled.launch"), data + "/launch/bundled.launch");
  LaunchCommand command;
  command.file = "bundled.launch";
  EXPECT_EQ(PlanLaunch("mrsim", command).name, "two");
  EXPECT_EQ(FindLaunchFile("./bundled.launch"), "./bundled.launch");
  EXPECT_EQ(FindLaunchFile("missing.launch"), "missing.launch");
  unsetenv("MRSIM_DATA_DIR");
}

TEST(LaunchCommand, AStopBeforeTheFirstStartStartsNothing) {
  LaunchCommand command;
  command.file = WriteFile("two.launch", kTwo);
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  EXPECT_EQ(RunLaunch(
                PlanLaunch("mrsim", command), [] { return true; }, out),
            0);
  std::rewind(out);
  std::string text;
  char buf[512];
  while (std::fgets(buf, sizeof buf, out)) text += buf;
  std::fclose(out);
  EXPECT_THAT(text, HasSubstr("stop requested"));
  EXPECT_THAT(text, ::testing::Not(HasSubstr("first: ")));
}

// What RunLaunch printed to `out` (a tmpfile), which it closes.
std::string TextOf(std::FILE* out) {
  std::rewind(out);
  std::string text;
  char buf[512];
  while (std::fgets(buf, sizeof buf, out)) text += buf;
  std::fclose(out);
  return text;
}

// A free TCP port on this host (closed again: a small race with other
// programs, none with other tests, which pick theirs the same way).
int FreeTcpPort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a));
  socklen_t size = sizeof(a);
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &size);
  close(fd);
  return ntohs(a.sin_port);
}

// A hub that takes a while to listen (a JVM starting): the clients after
// it start only once it accepts connections, since LCM's tcpq does not
// retry a refused first connection.
TEST(LaunchCommand, ProcessesAfterAHubStartOnceItListens) {
  const int port = FreeTcpPort();
  ASSERT_GT(port, 0);
  LaunchPlan plan;
  plan.name = "hub-first";
  ProcessSpec hub;
  hub.name = "hub";
  hub.program = "python3";
  hub.args = {"-c",
              "import socket, time\n"
              "time.sleep(1)\n"
              "s = socket.socket()\n"
              "s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)\n"
              "s.bind(('127.0.0.1', " +
                  std::to_string(port) +
                  "))\n"
                  "s.listen()\n"
                  "time.sleep(120)\n"};
  hub.ready_port = port;
  ProcessSpec client;
  client.name = "client";
  client.program = "python3";
  client.required = true;
  client.args = {"-c",
                 "import socket\n"
                 "socket.create_connection(('127.0.0.1', " +
                     std::to_string(port) +
                     "))\n"
                     "print('connected')\n"};
  const std::string python = FindProgram("python3", ProgramSearchPath("mrsim"));
  plan.processes = {{hub, python}, {client, python}};
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  const int code = RunLaunch(
      plan, [] { return false; }, out);
  const std::string text = TextOf(out);
  EXPECT_EQ(code, 0) << text;
  EXPECT_THAT(text, HasSubstr("connected")) << text;
  EXPECT_THAT(text, ::testing::Not(HasSubstr("refused"))) << text;
}

// A viewer setting up its renderer on a busy machine: what comes after it
// starts once it says it listens, not after a guessed delay.
TEST(LaunchCommand, ProcessesAfterOneWithAReadyLineStartOnceItPrintsIt) {
  LaunchPlan plan;
  plan.name = "ready-first";
  ProcessSpec slow;
  slow.name = "slow";
  slow.ready_line = "listening on \\d+";
  slow.args = {"-c",
               "echo setting up; sleep 1; echo listening on; "
               "echo listening on 3 channels; exec sleep 60"};
  ProcessSpec next;
  next.name = "next";
  next.required = true;
  next.args = {"-c", "echo next ran"};
  plan.processes = {{slow, "/bin/sh"}, {next, "/bin/sh"}};
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  const int code = RunLaunch(
      plan, [] { return false; }, out);
  const std::string text = TextOf(out);
  EXPECT_EQ(code, 0) << text;
  const size_t ready = text.find("listening on 3 channels");
  const size_t started = text.find("started next");
  ASSERT_NE(ready, std::string::npos) << text;
  ASSERT_NE(started, std::string::npos) << text;
  EXPECT_LT(ready, started) << text;
}

TEST(LaunchCommand, AProcessThatEndsBeforeItsReadyLineFailsTheLaunch) {
  LaunchPlan plan;
  plan.name = "never-ready";
  ProcessSpec broken;
  broken.name = "broken";
  broken.ready_line = "listening on";
  broken.args = {"-c", "echo cannot open the display; exit 0"};
  ProcessSpec next;
  next.name = "next";
  next.required = true;
  next.args = {"-c", "echo next ran"};
  plan.processes = {{broken, "/bin/sh"}, {next, "/bin/sh"}};
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  const int code = RunLaunch(
      plan, [] { return false; }, out);
  const std::string text = TextOf(out);
  EXPECT_EQ(code, 1) << text;
  EXPECT_THAT(text, HasSubstr("broken (ended before printing a line matching "
                              "'listening on')"))
      << text;
  EXPECT_THAT(text, ::testing::Not(HasSubstr("next ran"))) << text;
}

}  // namespace
}  // namespace mrsim

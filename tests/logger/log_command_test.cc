#include "logger/process/log_command.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>

#include "tests/common/child_process.h"
#include "tests/logger/csv_reader.h"
#include "tests/logger/test_messages.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

// Writes an .lcmlog holding `count` robot states on `channel`.
void WriteLog(const std::string& path, const std::string& channel, int count) {
  lcm::LogFile log(path, "w");
  ASSERT_TRUE(log.good());
  for (int seq = 0; seq < count; ++seq) {
    robot_state_t msg = testing::KnownRobotState(seq, 3, 1);
    std::vector<uint8_t> bytes(msg.getEncodedSize());
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    lcm::LogEvent ev{};
    ev.eventnum = seq;
    ev.timestamp = 1000 * seq;
    ev.channel = channel;
    ev.datalen = static_cast<int32_t>(bytes.size());
    ev.data = bytes.data();
    log.writeEvent(&ev);
  }
}

// Runs the command on a log; returns the exit status and what it printed.
int Replay(LogCommand command, std::string* printed = nullptr) {
  std::FILE* err = std::tmpfile();
  const LogPlan plan = PlanLog(command);
  const int status = RunLogCommand(command, plan, nullptr, err);
  std::fflush(err);
  std::rewind(err);
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, err)) > 0) text.append(buf, n);
  std::fclose(err);
  if (printed != nullptr) *printed = text;
  return status;
}

TEST(LogCommand, ChannelListsBecomeLiteralAlternatives) {
  EXPECT_EQ(ChannelRegex("MRSIM_STATE_.*"), "MRSIM_STATE_.*");
  EXPECT_EQ(ChannelRegex("A.B,C"), "A\\.B|C");
  EXPECT_EQ(ChannelRegex("A,,B,"), "A|B");
}

TEST(LogCommand, FlagsAndBadInputAreCheckedBeforeRecording) {
  CLI::App app;
  LogCommand c;
  AddLogFlags(app, c);
  // CLI11 takes the arguments last first.
  app.parse(std::vector<std::string>{"--quiet", "/tmp/x", "--out",
                                     "MRSIM_STATE_.*", "--channels"});
  EXPECT_EQ(c.channels, "MRSIM_STATE_.*");
  EXPECT_EQ(c.out_dir, "/tmp/x");
  EXPECT_TRUE(c.quiet);
  EXPECT_EQ(PlanLog(c).regex, "MRSIM_STATE_.*");

  LogCommand bad_regex;
  bad_regex.channels = "MRSIM_(";
  EXPECT_THROW(PlanLog(bad_regex), LogInputError);
  LogCommand bad_plot;
  bad_plot.plots = {"CHAN:x=time"};
  EXPECT_THROW(PlanLog(bad_plot), LogInputError);
  LogCommand missing;
  missing.from_log = testing::TempDir("log_command_missing") + "/none.lcmlog";
  EXPECT_THROW(PlanLog(missing), LogInputError);
}

TEST(LogCommand, ReplayWritesOneRowPerStateAndTheSummary) {
  const std::string dir = testing::TempDir("log_command_replay");
  WriteLog(dir + "/run.lcmlog", "MRSIM_STATE_snake", 25);
  LogCommand c;
  c.from_log = dir + "/run.lcmlog";
  c.out_dir = dir + "/csv";
  std::string printed;
  EXPECT_EQ(Replay(c, &printed), 0);
  EXPECT_NE(printed.find("25 messages"), std::string::npos) << printed;
  EXPECT_EQ(
      testing::ReadCsvFile(dir + "/csv/MRSIM_STATE_snake.csv").rows.size(),
      25u);
}

TEST(LogCommand, FileThatIsNotAnLcmLogIsBadInputAndWritesNothing) {
  const std::string dir = testing::TempDir("log_command_not_lcm");
  std::ofstream(dir + "/notes.txt") << "these are notes, not an LCM log\n"
                                    << std::string(5000, 'x');
  LogCommand c;
  c.from_log = dir + "/notes.txt";
  c.out_dir = dir + "/csv";
  try {
    Replay(c);
    ADD_FAILURE() << "no error";
  } catch (const LogInputError& e) {
    EXPECT_NE(std::string(e.what()).find("notes.txt: not an LCM log"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir + "/csv"));  // not even an empty folder
}

TEST(LogCommand, LogWithoutTheChannelsAskedIsBadInputNamingWhatItHas) {
  const std::string dir = testing::TempDir("log_command_other_channels");
  WriteLog(dir + "/run.lcmlog", "OTHER_STATE_snake", 5);
  LogCommand c;
  c.from_log = dir + "/run.lcmlog";
  c.out_dir = dir + "/csv";
  try {
    Replay(c);
    ADD_FAILURE() << "no error";
  } catch (const LogInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no message on channels matching 'MRSIM_.*'"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("OTHER_STATE_snake"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(dir + "/csv"));  // not even an empty folder
}

}  // namespace
}  // namespace mrsim

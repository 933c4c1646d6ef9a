// mrsim-log as a real process, fed by this test over real LCM.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "mrsim/sim_status_t.hpp"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/logger/csv_reader.h"
#include "tests/logger/test_messages.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::TempDir;
using testing::TestLcmUrl;

const char* const kStateChannel = "MRSIM_STATE_snake";

std::string LogExe() { return BinaryPath("logger/process/mrsim-log"); }

// Starts mrsim-log on `url` writing to `dir`; returns once it has
// subscribed (it says so after subscribing).
std::unique_ptr<ChildProcess> StartLogger(const std::string& url,
                                          const std::string& dir,
                                          std::vector<std::string> extra = {}) {
  std::vector<std::string> argv = {LogExe(), "--lcm-url", url, "--out", dir};
  argv.insert(argv.end(), extra.begin(), extra.end());
  auto p = std::make_unique<ChildProcess>(argv, dir + ".out.txt");
  EXPECT_TRUE(p->WaitForOutput("recording channels", 30)) << p->Output();
  return p;
}

// Publishes states seq = 0..count-1 (skipping `skip`) at once: mrsim-log
// asks for a receive buffer (--recv-buf-size) that holds far more than
// these few hundred small messages, so nothing needs pacing.
void PublishStates(lcm::LCM& lcm, int count, int modules,
                   const std::vector<int64_t>& skip = {}) {
  for (int64_t seq = 0; seq < count; ++seq) {
    if (std::find(skip.begin(), skip.end(), seq) != skip.end()) continue;
    const robot_state_t msg = testing::KnownRobotState(seq, modules, 1);
    lcm.publish(kStateChannel, &msg);
  }
}

// Waits until `channel`'s CSV in `dir` holds `rows` rows (mrsim-log flushes
// every half second), so stopping it then loses nothing in flight.
bool WaitForRows(const std::string& dir, const std::string& channel,
                 size_t rows, double timeout_s = 30) {
  return testing::WaitForLines(dir + "/" + channel + ".csv", rows + 1,
                               timeout_s);
}

double Parse(const std::string& s) {
  double v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}

TEST(LoggerProcess, KnownNumberOfStatesGivesThatManyRowsWithTheValuesSent) {
  const std::string url = TestLcmUrl(7750);
  const std::string dir = TempDir("logger_known_count");
  auto logger = StartLogger(url, dir);
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  constexpr int kCount = 500;
  PublishStates(lcm, kCount, 4);
  ASSERT_TRUE(WaitForRows(dir, kStateChannel, kCount)) << logger->Output();
  EXPECT_EQ(logger->Stop(10), 0) << logger->Output();

  const auto csv = testing::ReadCsvFile(dir + "/" + kStateChannel + ".csv");
  ASSERT_EQ(csv.rows.size(), static_cast<size_t>(kCount)) << logger->Output();
  const int seq_col = csv.Column("seq");
  const int angle_col = csv.Column("module2.joint.angle");
  const int dist_col = csv.Column("sensor_module0.distance4");
  const int time_col = csv.Column("time");
  ASSERT_GE(seq_col, 0);
  ASSERT_GE(angle_col, 0);
  ASSERT_GE(dist_col, 0);
  ASSERT_GE(time_col, 0);
  for (int i = 0; i < kCount; ++i) {
    const auto& row = csv.rows[i];
    ASSERT_EQ(row.size(), csv.header.size()) << "row " << i;
    const robot_state_t sent = testing::KnownRobotState(i, 4, 1);
    EXPECT_EQ(row[seq_col], std::to_string(i));
    EXPECT_EQ(Parse(row[time_col]), static_cast<double>(sent.utime) / 1e6);
    EXPECT_EQ(Parse(row[angle_col]), sent.joints[2].angle);
    EXPECT_EQ(Parse(row[dist_col]), sent.sensor_modules[0].distance[1]);
  }
  EXPECT_NE(logger->Output().find("0 gaps (0 missing)"), std::string::npos)
      << logger->Output();
}

TEST(LoggerProcess, LcmlogReplayGivesTheSameCsvAsLive) {
  const std::string url = TestLcmUrl(7751);
  const std::string dir = TempDir("logger_replay");
  const std::string live_dir = dir + "/live";
  const std::string replay_dir = dir + "/replay";
  const std::string lcmlog = dir + "/run.lcmlog";
  ChildProcess recorder({"/usr/bin/lcm-logger", "--lcm-url=" + url, lcmlog},
                        dir + "/lcm-logger.txt");
  auto logger = StartLogger(url, live_dir);
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  // lcm-logger says nothing when ready, queues at most 30 messages it has
  // not handled, and flushes only as messages come. So a probe on a channel
  // mrsim-log does not record is repeated until it is in the file: then
  // lcm-logger listens, and has handled everything sent before the probe
  // (one host keeps UDP's order). States go in rounds of 20 between probes.
  int probes = 0;
  auto probe = [&]() {
    const std::string name = "PROBE_" + std::to_string(probes++) + "_";
    const uint8_t byte[1] = {0};
    return testing::RepeatUntil(
        [&] { lcm.publish(name, byte, sizeof byte); },
        [&] {
          return testing::ReadFileText(lcmlog).find(name) != std::string::npos;
        },
        0.02, 30);
  };
  ASSERT_TRUE(probe()) << recorder.Output();
  for (int64_t seq = 0; seq < 200; ++seq) {
    const robot_state_t msg = testing::KnownRobotState(seq, 3, 1);
    lcm.publish(kStateChannel, &msg);
    if (seq % 20 == 19) {
      ASSERT_TRUE(probe()) << recorder.Output();
    }
  }
  sim_status_t st{};
  st.utime = 123456;
  st.seq = 0;
  st.clock = "fast";
  st.last_error = "none, really";
  lcm.publish("MRSIM_SIM_STATUS", &st);
  ASSERT_TRUE(probe()) << recorder.Output();
  ASSERT_TRUE(WaitForRows(live_dir, "MRSIM_SIM_STATUS", 1)) << logger->Output();
  EXPECT_EQ(logger->Stop(10), 0) << logger->Output();
  recorder.Signal(SIGINT);
  EXPECT_EQ(recorder.Wait(10), 0);

  ChildProcess replay({LogExe(), "--from-log", lcmlog, "--out", replay_dir},
                      dir + "/replay.txt");
  ASSERT_EQ(replay.Wait(30), 0) << replay.Output();
  for (const std::string ch : {kStateChannel, "MRSIM_SIM_STATUS"}) {
    const std::string live = testing::ReadText(live_dir + "/" + ch + ".csv");
    const std::string replayed =
        testing::ReadText(replay_dir + "/" + ch + ".csv");
    EXPECT_FALSE(live.empty()) << ch;
    EXPECT_TRUE(live == replayed) << ch << " differs between live and replay";
  }
  EXPECT_EQ(testing::ReadCsvFile(replay_dir + "/" + kStateChannel + ".csv")
                .rows.size(),
            200u);
}

TEST(LoggerProcess, SigtermMidRunLeavesAWholeLastLine) {
  const std::string url = TestLcmUrl(7752);
  const std::string dir = TempDir("logger_sigterm");
  auto logger = StartLogger(url, dir);
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  // A 1 kHz source, as mrsim-sim is, still sending when the signal comes.
  std::atomic<bool> stop{false};
  std::thread publisher([&] {
    int64_t seq = 0;
    testing::RepeatUntil(
        [&] {
          const robot_state_t msg = testing::KnownRobotState(seq++, 10, 2);
          lcm.publish(kStateChannel, &msg);
        },
        [&] { return stop.load(); }, 0.001, 120);
  });
  // Mid-run: rows already written, more arriving.
  EXPECT_TRUE(WaitForRows(dir, kStateChannel, 11)) << logger->Output();
  logger->Signal(SIGTERM);
  const int code = logger->Wait(10);
  stop = true;
  publisher.join();
  EXPECT_EQ(code, 0) << logger->Output();

  const auto csv = testing::ReadCsvFile(dir + "/" + kStateChannel + ".csv");
  ASSERT_FALSE(csv.text.empty());
  EXPECT_EQ(csv.text.back(), '\n');
  ASSERT_GT(csv.rows.size(), 10u);
  for (size_t i = 0; i < csv.rows.size(); ++i) {
    ASSERT_EQ(csv.rows[i].size(), csv.header.size()) << "row " << i;
  }
}

// A wrong --prefix (or --lcm-url) records nothing: said, and not a success.
TEST(LoggerProcess, NothingRecordedIsSaidAndFails) {
  const std::string url = TestLcmUrl(7759);
  const std::string dir = TempDir("logger_nothing");
  auto logger = StartLogger(url, dir, {"--prefix", "MRSM"});
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  PublishStates(lcm, 5, 2);  // on MRSIM_STATE_snake, not MRSM_
  logger->Signal(SIGINT);
  EXPECT_EQ(logger->Wait(30), 1) << logger->Output();
  EXPECT_NE(logger->Output().find("nothing recorded: no message on channels "
                                  "matching 'MRSM_.*'"),
            std::string::npos)
      << logger->Output();
}

TEST(LoggerProcess, SkippedSequenceNumbersAreReportedAsGaps) {
  const std::string url = TestLcmUrl(7753);
  const std::string dir = TempDir("logger_gaps");
  auto logger = StartLogger(url, dir);
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  PublishStates(lcm, 50, 2, {10, 11, 12, 30});
  ASSERT_TRUE(WaitForRows(dir, kStateChannel, 46)) << logger->Output();
  EXPECT_EQ(logger->Stop(10), 0);
  const std::string out = logger->Output();
  EXPECT_NE(out.find("gap: seq 10..12 missing (3 messages)"), std::string::npos)
      << out;
  EXPECT_NE(out.find("gap: seq 30 missing (1 messages)"), std::string::npos)
      << out;
  EXPECT_NE(out.find("2 gaps (4 missing)"), std::string::npos) << out;
  EXPECT_EQ(
      testing::ReadCsvFile(dir + "/" + kStateChannel + ".csv").rows.size(),
      46u);
}

TEST(LoggerProcess, UnwritableFolderGivesAClearErrorAndNonZeroExit) {
  const std::string dir = TempDir("logger_unwritable");
  // A folder below a regular file cannot be made, even by root.
  const std::string file = dir + "/plain_file";
  { std::ofstream(file) << "x"; }
  const std::string out = file + "/csv";
  ChildProcess logger({LogExe(), "--lcm-url", TestLcmUrl(7754), "--out", out},
                      dir + "/out.txt");
  const int code = logger.Wait(20);
  EXPECT_NE(code, 0);
  EXPECT_NE(code, -1);
  EXPECT_NE(logger.Output().find(out), std::string::npos) << logger.Output();
}

TEST(LoggerProcess, FullDiskGivesAClearErrorAndKeepsTheOtherFiles) {
  const std::string url = TestLcmUrl(7755);
  const std::string dir = TempDir("logger_full_disk");
  const std::string full = dir + "/MRSIM_STATE_full.csv";
  std::filesystem::create_symlink("/dev/full", full);
  auto logger = StartLogger(url, dir);
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  for (int64_t seq = 0; seq < 20; ++seq) {
    const robot_state_t msg = testing::KnownRobotState(seq, 2, 0);
    lcm.publish(kStateChannel, &msg);
  }
  // Written before the full disk fails the other file.
  ASSERT_TRUE(WaitForRows(dir, kStateChannel, 20)) << logger->Output();
  for (int64_t seq = 0; seq < 5; ++seq) {
    const robot_state_t msg = testing::KnownRobotState(seq, 2, 0, "full");
    lcm.publish("MRSIM_STATE_full", &msg);
  }
  const int code = logger->Wait(10);
  EXPECT_EQ(code, 1) << logger->Output();
  const std::string out = logger->Output();
  EXPECT_NE(out.find("cannot write " + full), std::string::npos) << out;
  const auto csv = testing::ReadCsvFile(dir + "/" + kStateChannel + ".csv");
  EXPECT_EQ(csv.rows.size(), 20u);
  EXPECT_EQ(csv.text.back(), '\n');
}

TEST(LoggerProcess, OtherTypesDecodeByFingerprintAndUnknownOnesAreCounted) {
  const std::string url = TestLcmUrl(7756);
  const std::string dir = TempDir("logger_types");
  auto logger = StartLogger(url, dir, {"--channels", ".*"});
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  sim_status_t st{};
  st.utime = 1000000;
  st.clock = "real";
  for (int64_t seq = 0; seq < 3; ++seq) {
    st.seq = seq;
    st.steps = 100 * seq;
    lcm.publish("ANY_NAME_AT_ALL", &st);
  }
  const uint8_t junk[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  lcm.publish("FOREIGN", junk, sizeof(junk));
  lcm.publish("FOREIGN", junk, sizeof(junk));
  // Sent last: once its row is written, the foreign ones were counted.
  st.seq = 3;
  lcm.publish("ANY_NAME_AT_ALL", &st);
  ASSERT_TRUE(WaitForRows(dir, "ANY_NAME_AT_ALL", 4)) << logger->Output();
  EXPECT_EQ(logger->Stop(10), 0);
  const auto csv = testing::ReadCsvFile(dir + "/ANY_NAME_AT_ALL.csv");
  ASSERT_EQ(csv.rows.size(), 4u);
  EXPECT_EQ(csv.rows[2][csv.Column("steps")], "200");
  EXPECT_FALSE(std::filesystem::exists(dir + "/FOREIGN.csv"));
  EXPECT_NE(logger->Output().find("FOREIGN: 2 messages of unknown type"),
            std::string::npos)
      << logger->Output();
}

TEST(LoggerProcess, WritesTheCaseStudyPlotsWhenLoggingStops) {
  const std::string url = TestLcmUrl(7757);
  const std::string dir = TempDir("logger_plots");
  auto logger = StartLogger(
      url, dir,
      {"--plot",
       std::string(kStateChannel) +
           ":y=sensor_module0.distance0:title=Front distance:distance.png",
       "--plot",
       std::string(kStateChannel) +
           ":x=module0.z:y=sensor_module0.force:out=force.png"});
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  PublishStates(lcm, 100, 2);
  ASSERT_TRUE(WaitForRows(dir, kStateChannel, 100)) << logger->Output();
  EXPECT_EQ(logger->Stop(20), 0) << logger->Output();
  for (const std::string png : {"distance.png", "force.png"}) {
    const cv::Mat img = cv::imread(dir + "/" + png);
    EXPECT_FALSE(img.empty()) << png << "\n" << logger->Output();
  }
}

TEST(LoggerProcess, MissingLcmlogIsBadInput) {
  const std::string dir = TempDir("logger_missing_log");
  ChildProcess logger(
      {LogExe(), "--from-log", dir + "/nothing.lcmlog", "--out", dir + "/csv"},
      dir + "/out.txt");
  EXPECT_EQ(logger.Wait(20), 2);
  EXPECT_NE(logger.Output().find(dir + "/nothing.lcmlog"), std::string::npos)
      << logger.Output();
}

TEST(LoggerProcess, FileThatIsNotAnLcmLogExitsTwoNamingIt) {
  const std::string dir = TempDir("logger_not_lcm");
  std::ofstream(dir + "/plain.txt") << "not an LCM log\n";
  ChildProcess logger(
      {LogExe(), "--from-log", dir + "/plain.txt", "--out", dir + "/csv"},
      dir + "/out.txt");
  EXPECT_EQ(logger.Wait(20), 2);
  EXPECT_NE(logger.Output().find("plain.txt: not an LCM log"),
            std::string::npos)
      << logger.Output();
}

TEST(LoggerProcess, BadPlotSpecIsRefusedBeforeLogging) {
  ChildProcess logger({LogExe(), "--lcm-url", TestLcmUrl(7758), "--out",
                       TempDir("logger_bad_plot"), "--plot", "CHAN:x=time"},
                      TempDir("logger_bad_plot") + "/../bad_plot.txt");
  EXPECT_EQ(logger.Wait(20), 2);
  EXPECT_NE(logger.Output().find("no y=COLUMN"), std::string::npos)
      << logger.Output();
}

}  // namespace
}  // namespace mrsim

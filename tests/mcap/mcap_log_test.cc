// mrsim-log --mcap as a real process, fed over real LCM, its files opened
// by the format's reference reader (@mcap/core, tests/mcap/read_mcap.js):
// indexed and CRC-checked with as many state messages as the CSV logger
// wrote rows on the same traffic; streamed up to the last chunk when the
// logger was killed; converted from an lcm-logger log, protobuf (decoded
// with protobufjs from the file's schema) and JSON reading the same.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <regex>
#include <string>
#include <vector>

#include "logger/mcap/mcap_reader.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/logger/test_messages.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

const char* const kStateChannel = "MRSIM_STATE_snake";

std::string LogExe() { return BinaryPath("logger/process/mrsim-log"); }

// Why the reference reader cannot run, or "" when it can.
std::string NodeMissing() {
  if (!std::filesystem::exists(
          SourcePath("tests/mcap/node_modules/@mcap/core/package.json")) ||
      !std::filesystem::exists(
          SourcePath("tests/mcap/node_modules/protobufjs/package.json"))) {
    return "tests/mcap/node_modules is missing: scripts/install_deps.sh "
           "installs it (npm ci in tests/mcap)";
  }
  if (std::system("node --version > /dev/null 2>&1") != 0) {
    return "node is not installed: scripts/install_deps.sh installs it";
  }
  return "";
}

// read_mcap.js's output for `file` (mode "indexed" or "stream"); fails the
// test when the reader refused the file.
std::string ReadWithNode(const std::string& mode, const std::string& file) {
  const std::string out = file + "." + mode + ".json";
  ChildProcess node({"/usr/bin/env", "node",
                     SourcePath("tests/mcap/read_mcap.js"), mode, file},
                    out);
  const int status = node.Wait(120);
  EXPECT_EQ(status, 0) << mode << " " << file << ": " << node.Output();
  return node.Output();
}

// read_mcap.js's comparison of two files' messages ("same").
std::string SameWithNode(const std::string& a, const std::string& b) {
  const std::string out = b + ".same.json";
  ChildProcess node({"/usr/bin/env", "node",
                     SourcePath("tests/mcap/read_mcap.js"), "same", a, b},
                    out);
  const int status = node.Wait(120);
  EXPECT_EQ(status, 0) << "same " << a << " " << b << ": " << node.Output();
  return node.Output();
}

// "count" of a topic in read_mcap.js's output, -1 when absent.
int64_t Count(const std::string& json, const std::string& topic) {
  std::smatch m;
  const std::regex re("\"" + topic + "\":\\{\"count\":(\\d+)");
  return std::regex_search(json, m, re) ? std::stoll(m[1]) : -1;
}

std::unique_ptr<ChildProcess> StartLogger(const std::string& url,
                                          const std::vector<std::string>& how,
                                          const std::string& out_txt) {
  std::vector<std::string> argv = {LogExe(), "--lcm-url", url};
  argv.insert(argv.end(), how.begin(), how.end());
  auto p = std::make_unique<ChildProcess>(argv, out_txt);
  EXPECT_TRUE(p->WaitForOutput("recording channels", 30)) << p->Output();
  return p;
}

TEST(McapLog, IndexedFileHoldsAsManyStatesAsTheCsvLoggerWroteRows) {
  const std::string skip = NodeMissing();
  if (!skip.empty()) GTEST_SKIP() << skip;
  const std::string url = TestLcmUrl(8110);
  const std::string dir = TempDir("mcap_log_vs_csv");
  const std::string mcap = dir + "/run.mcap";
  auto csv = StartLogger(url, {"--out", dir + "/csv"}, dir + "/csv.txt");
  auto logger = StartLogger(url, {"--mcap", mcap}, dir + "/mcap.txt");
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  // seq 0..399 without 50 and 51, and seq 10 sent twice (a lockstep
  // re-send): 398 rows, the same in both.
  for (int64_t seq = 0; seq < 400; ++seq) {
    if (seq == 50 || seq == 51) continue;
    const robot_state_t msg = testing::KnownRobotState(seq, 4, 1);
    lcm.publish(kStateChannel, &msg);
    if (seq == 10) lcm.publish(kStateChannel, &msg);
  }
  ASSERT_TRUE(testing::WaitForLines(
      dir + "/csv/" + std::string(kStateChannel) + ".csv", 398 + 1, 30))
      << csv->Output();
  EXPECT_EQ(csv->Stop(10), 0) << csv->Output();
  EXPECT_EQ(logger->Stop(10), 0) << logger->Output();
  const int64_t rows =
      static_cast<int64_t>(testing::CountLines(
          dir + "/csv/" + std::string(kStateChannel) + ".csv")) -
      1;
  EXPECT_EQ(rows, 398);
  EXPECT_NE(logger->Output().find("1 gaps (2 missing), 1 re-sends skipped"),
            std::string::npos)
      << logger->Output();
  const std::string json = ReadWithNode("indexed", mcap);
  EXPECT_EQ(Count(json, kStateChannel), rows) << json.substr(0, 300);
  EXPECT_NE(
      json.find("\"schema\":\"mrsim.robot_state_t\","
                "\"schemaEncoding\":\"protobuf\",\"encoding\":\"protobuf\""),
      std::string::npos)
      << json.substr(0, 300);
  EXPECT_NE(json.find("\"dataSectionCrc\":true"), std::string::npos);
}

TEST(McapLog, KilledLoggerLeavesAFileReadUpToItsLastChunk) {
  const std::string skip = NodeMissing();
  if (!skip.empty()) GTEST_SKIP() << skip;
  const std::string url = TestLcmUrl(8111);
  const std::string dir = TempDir("mcap_log_killed");
  const std::string mcap = dir + "/run.mcap";
  auto logger = StartLogger(url, {"--mcap", mcap}, dir + "/mcap.txt");
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  // States at 100 Hz until a chunk is in the file (the logger closes one a
  // second), then a few more that stay in the chunk the kill loses.
  int64_t seq = 0;
  const auto in_file = [&] {
    int64_t n = 0;
    try {
      mcap::ReadMcap(testing::ReadFileText(mcap), mcap,
                     [&](const mcap::McapMessage&) { ++n; });
    } catch (const mcap::McapError&) {
    }
    return n;
  };
  ASSERT_TRUE(testing::RepeatUntil(
      [&] {
        const robot_state_t msg = testing::KnownRobotState(seq++, 4, 1);
        lcm.publish(kStateChannel, &msg);
      },
      [&] { return in_file() > 0; }, 0.01, 30))
      << logger->Output();
  for (int i = 0; i < 10; ++i) {
    const robot_state_t msg = testing::KnownRobotState(seq++, 4, 1);
    lcm.publish(kStateChannel, &msg);
  }
  logger->Signal(SIGKILL);
  logger->Wait(10);
  const int64_t chunked = in_file();
  const std::string json = ReadWithNode("stream", mcap);
  EXPECT_NE(json.find("\"complete\":false"), std::string::npos) << json;
  EXPECT_EQ(Count(json, kStateChannel), chunked) << json.substr(0, 300);
  EXPECT_GT(chunked, 0);
  // In order from the first: "seqs":[0,1,2,...].
  EXPECT_NE(json.find("\"seqs\":[0,1,2,"), std::string::npos)
      << json.substr(0, 300);
}

TEST(McapLog,
     LcmLoggerLogConvertsToAnIndexedFileInEitherEncodingCompressedOrNot) {
  const std::string skip = NodeMissing();
  if (!skip.empty()) GTEST_SKIP() << skip;
  const std::string dir = TempDir("mcap_log_from");
  const std::string lcmlog = dir + "/run.lcmlog";
  {
    lcm::LogFile log(lcmlog, "w");
    ASSERT_TRUE(log.good());
    for (int64_t seq = 0; seq < 250; ++seq) {
      const robot_state_t msg = testing::KnownRobotState(seq, 3, 1);
      std::vector<uint8_t> buf(msg.getEncodedSize());
      msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
      lcm::LogEvent ev;
      ev.eventnum = seq;
      ev.timestamp = 1700000000000000 + 1000 * seq;
      ev.channel = kStateChannel;
      ev.datalen = static_cast<int32_t>(buf.size());
      ev.data = buf.data();
      ASSERT_EQ(log.writeEvent(&ev), 0);
    }
  }
  const std::string mcap = dir + "/run.mcap";
  ChildProcess convert({LogExe(), "--from", lcmlog, "--mcap", mcap},
                       dir + "/convert.txt");
  ASSERT_EQ(convert.Wait(60), 0) << convert.Output();
  const std::string json = ReadWithNode("indexed", mcap);
  EXPECT_EQ(Count(json, kStateChannel), 250) << json.substr(0, 300);
  EXPECT_NE(json.find("\"messageCount\":250"), std::string::npos) << json;
  // Uncompressed chunks (less CPU, a larger file) read the same.
  const std::string plain = dir + "/plain.mcap";
  ChildProcess convert_plain({LogExe(), "--from", lcmlog, "--mcap", plain,
                              "--mcap-compression", "none"},
                             dir + "/convert_plain.txt");
  ASSERT_EQ(convert_plain.Wait(60), 0) << convert_plain.Output();
  const std::string plain_json = ReadWithNode("indexed", plain);
  EXPECT_EQ(Count(plain_json, kStateChannel), 250) << plain_json.substr(0, 300);
  EXPECT_NE(plain_json.find("\"dataSectionCrc\":true"), std::string::npos)
      << plain_json.substr(0, 300);

  // The JSON encoding of the same log: @mcap/core with protobufjs reads
  // every state of the protobuf file as the same values.
  const std::string as_json = dir + "/json.mcap";
  ChildProcess convert_json({LogExe(), "--from", lcmlog, "--mcap", as_json,
                             "--mcap-encoding", "json"},
                            dir + "/convert_json.txt");
  ASSERT_EQ(convert_json.Wait(60), 0) << convert_json.Output();
  const std::string json_json = ReadWithNode("indexed", as_json);
  EXPECT_NE(json_json.find("\"schemaEncoding\":\"jsonschema\","
                           "\"encoding\":\"json\""),
            std::string::npos)
      << json_json.substr(0, 300);
  EXPECT_EQ(SameWithNode(as_json, mcap),
            "{\"compared\":250,\"differ\":0,\"first_difference\":\"\"}\n");
}

}  // namespace
}  // namespace mrsim

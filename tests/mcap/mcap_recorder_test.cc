// McapRecorder: LCM messages in, JSON messages with their schemas out, with
// the CSV Recorder's counts (gaps, re-sends, malformed, unknown types);
// JsonWriter's text for what JSON cannot hold as it is.
#include "logger/mcap/mcap_recorder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "lcmtypes/json/json_writer.h"
#include "logger/mcap/mcap_reader.h"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/message_json.hpp"
#include "mrsim/sim_status_t.hpp"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/logger/test_messages.h"

namespace mrsim {
namespace {

template <class T>
std::vector<uint8_t> Encode(const T& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

struct Read {
  mcap::McapSummary summary;
  std::vector<std::string> topics, data;
};

Read ReadBack(const std::string& path) {
  Read r;
  r.summary = mcap::ReadMcap(testing::ReadFileText(path), path,
                             [&](const mcap::McapMessage& m) {
                               r.topics.push_back(m.channel->topic);
                               r.data.emplace_back(m.data);
                             });
  return r;
}

TEST(McapRecorder, CountsGapsResendsAndBadMessagesAsTheCsvRecorderDoes) {
  const std::string path = testing::TempDir("mcap_recorder") + "/run.mcap";
  std::vector<std::string> reports;
  McapRecorderOptions options;
  options.path = path;
  options.report = [&](const std::string& s) { reports.push_back(s); };
  options.encoding = McapEncoding::kJson;  // the data read back below
  McapRecorder recorder(options);
  const std::string channel = "MRSIM_STATE_snake";
  uint64_t t = 1000;
  for (int64_t seq : {0, 1, 2, 3, 3, 4, 7, 8}) {  // 3 re-sent, 5-6 lost
    const auto bytes = Encode(testing::KnownRobotState(seq, 3, 1));
    recorder.OnMessage(channel, bytes.data(), bytes.size(), t += 1000);
  }
  auto bad = Encode(testing::KnownRobotState(9, 3, 1));
  bad.resize(bad.size() / 2);
  recorder.OnMessage(channel, bad.data(), bad.size(), t += 1000);
  const std::vector<uint8_t> unknown(64, 0x5a);
  recorder.OnMessage("MRSIM_OTHER", unknown.data(), unknown.size(), t);
  recorder.Finish();

  const std::vector<ChannelStats> stats = recorder.Stats();
  ASSERT_EQ(stats.size(), 2u);
  const ChannelStats& s = stats[1];
  EXPECT_EQ(s.channel, channel);
  EXPECT_EQ(s.type, "mrsim.robot_state_t");
  EXPECT_EQ(s.messages, 9);
  EXPECT_EQ(s.rows, 7);
  EXPECT_EQ(s.repeats, 1);
  EXPECT_EQ(s.gaps, 1);
  EXPECT_EQ(s.missing, 2);
  EXPECT_EQ(s.malformed, 1);
  EXPECT_EQ(stats[0].unknown_type, 1);
  EXPECT_NE(recorder.Summary().find("1 gaps (2 missing)"), std::string::npos)
      << recorder.Summary();

  const Read r = ReadBack(path);
  EXPECT_TRUE(r.summary.complete);
  ASSERT_EQ(r.data.size(), 7u);
  EXPECT_EQ(r.topics[0], channel);
  EXPECT_EQ(r.data[6].rfind("{\"utime\":8017,\"seq\":8,\"robot\":\"snake\"", 0),
            0u)
      << r.data[6].substr(0, 80);
  ASSERT_EQ(r.summary.schemas.size(), 1u);
  const mcap::McapSchema& schema = r.summary.schemas.begin()->second;
  EXPECT_EQ(schema.name, "mrsim.robot_state_t");
  EXPECT_EQ(schema.encoding, "jsonschema");
  EXPECT_NE(schema.data.find("\"num_modules\":{\"type\":\"integer\"}"),
            std::string::npos);
  EXPECT_EQ(r.summary.channels.begin()->second.message_encoding, "json");
}

TEST(McapRecorder, AChunkIsOnDiskOnceItsFirstMessageIsAPeriodOld) {
  const std::string path = testing::TempDir("mcap_period") + "/run.mcap";
  McapRecorderOptions options;
  options.path = path;
  options.chunk_period_ns = 1000000000;
  McapRecorder recorder(options);
  const auto bytes = Encode(testing::KnownRobotState(0, 3, 1));
  recorder.OnMessage("MRSIM_STATE_snake", bytes.data(), bytes.size(), 5e9);
  recorder.Tick(5.5e9);
  EXPECT_EQ(ReadBack(path).data.size(), 0u);  // still in the open chunk
  recorder.Tick(6e9);
  const Read r = ReadBack(path);  // the writer is still running
  EXPECT_FALSE(r.summary.complete);
  EXPECT_EQ(r.data.size(), 1u);
}

TEST(McapRecorder, LogTimesNeverGoBackEvenWhenReceiveTimesDo) {
  const std::string path = testing::TempDir("mcap_times") + "/run.mcap";
  McapRecorderOptions options;
  options.path = path;
  {
    McapRecorder recorder(options);
    for (int64_t seq = 0; seq < 3; ++seq) {
      const auto bytes = Encode(testing::KnownRobotState(seq, 2, 1));
      const uint64_t received[] = {5000, 1200, 7000};
      recorder.OnMessage("MRSIM_STATE_snake", bytes.data(), bytes.size(),
                         received[seq]);
    }
    recorder.Finish();
  }
  std::vector<uint64_t> times;
  mcap::ReadMcap(
      testing::ReadFileText(path), path,
      [&](const mcap::McapMessage& m) { times.push_back(m.log_time); });
  EXPECT_EQ(times, (std::vector<uint64_t>{5000, 5000, 7000}));
}

TEST(MessageJson, EveryTypeHasASchemaAndNumbersJsonCannotHoldAreNull) {
  EXPECT_GE(MessageJsonTypes().size(), 10u);
  for (const MessageJsonType& t : MessageJsonTypes()) {
    EXPECT_EQ(FindMessageJsonType(t.fingerprint), &t);
    EXPECT_NE(
        std::string(t.schema).find(std::string("\"title\":\"") + t.name + "\""),
        std::string::npos);
  }
  sim_status_t status{};
  status.sim_time = std::nan("");
  status.speed = INFINITY;
  status.clock = "fast";
  JsonWriter out;
  WriteJson(status, out);
  const std::string text(out.view());
  EXPECT_NE(text.find("\"sim_time\":null"), std::string::npos) << text;
  EXPECT_NE(text.find("\"speed\":null"), std::string::npos) << text;
  EXPECT_NE(text.find("\"clock\":\"fast\""), std::string::npos) << text;
}

TEST(MessageJson, StringsAreEscapedAndMadeValidUtf8) {
  JsonWriter out;
  out.String(std::string("a\"b\\c\n\x01 \xc3\xa9 \xff \xe2\x82", 15));
  EXPECT_EQ(std::string(out.view()),
            "\"a\\\"b\\\\c\\u000a\\u0001 \xc3\xa9 \\ufffd \\ufffd\\ufffd\"");
  out.Clear();
  out.Double(0.1);
  out.Raw(",");
  out.Double(-2.5e-7);
  out.Raw(",");
  out.Int(-9007199254740993);
  EXPECT_EQ(std::string(out.view()), "0.1,-2.5e-07,-9007199254740993");
}

TEST(MessageJson, AMessageThatIsNotWellFormedWritesNothing) {
  const MessageJsonType* t = FindMessageJsonType(robot_state_t::getHash());
  ASSERT_NE(t, nullptr);
  auto bytes = Encode(testing::KnownRobotState(4, 2, 1));
  JsonWriter out;
  int64_t seq = -1;
  EXPECT_TRUE(t->to_json(bytes.data(), bytes.size(), out, &seq));
  EXPECT_EQ(seq, 4);
  out.Clear();
  bytes.pop_back();
  EXPECT_FALSE(t->to_json(bytes.data(), bytes.size(), out, &seq));
  EXPECT_EQ(out.size(), 0u);
}

// In lockstep mrsim-camera answers with commands without targets between a
// controller's: each is written as it came, none with the one before's
// targets (the writer reuses its decoded message).
TEST(MessageJson, AnEmptyArrayAfterAFullOneIsWrittenEmpty) {
  const MessageJsonType* t = FindMessageJsonType(joint_command_t::getHash());
  ASSERT_NE(t, nullptr);
  auto json_of = [t](int joints) {
    joint_command_t cmd;
    cmd.robot = "snake";
    cmd.sender = joints > 0 ? "gait" : "mrsim-camera";
    cmd.num_joints = joints;
    cmd.target.assign(joints, 0.25);
    std::vector<uint8_t> b(static_cast<size_t>(cmd.getEncodedSize()));
    cmd.encode(b.data(), 0, static_cast<int>(b.size()));
    JsonWriter out;
    int64_t seq = 0;
    EXPECT_TRUE(t->to_json(b.data(), b.size(), out, &seq));
    return std::string(out.view());
  };
  EXPECT_NE(json_of(3).find("\"target\":[0.25,0.25,0.25]"), std::string::npos);
  const std::string empty = json_of(0);
  EXPECT_NE(empty.find("\"num_joints\":0,\"target\":[]"), std::string::npos)
      << empty;
}

}  // namespace
}  // namespace mrsim

// The recorder, writer and queue in-process (no network).
#include "logger/recorder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <thread>
#include <vector>

#include "lcmtypes/runtime/message_auth.h"
#include "logger/csv_writer.h"
#include "logger/message_queue.h"
#include "logger/seq_tracker.h"
#include "mrsim/joint_command_t.hpp"
#include "tests/common/child_process.h"
#include "tests/logger/csv_reader.h"
#include "tests/logger/test_messages.h"

namespace mrsim {
namespace {

std::vector<uint8_t> Encode(const robot_state_t& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

void Send(Recorder& rec, const std::string& channel, const robot_state_t& msg) {
  const auto b = Encode(msg);
  rec.OnMessage(channel, b.data(), b.size());
}

struct Capture {
  std::vector<std::string> lines;
  RecorderOptions Options(const std::string& dir) {
    RecorderOptions o;
    o.out_dir = dir;
    o.report = [this](const std::string& s) { lines.push_back(s); };
    return o;
  }
  bool Has(const std::string& text) const {
    for (const std::string& l : lines) {
      if (l.find(text) != std::string::npos) return true;
    }
    return false;
  }
};

TEST(LoggerRecorder, ShapeChangeContinuesInANewPartWithItsOwnHeader) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_parts");
  Capture cap;
  {
    Recorder rec(registry, cap.Options(dir));
    for (int64_t seq = 0; seq < 3; ++seq) {
      const auto b = Encode(testing::KnownRobotState(seq, 3, 1));
      rec.OnMessage("MRSIM_STATE_a", b.data(), b.size());
    }
    for (int64_t seq = 3; seq < 5; ++seq) {
      const auto b = Encode(testing::KnownRobotState(seq, 4, 1));
      rec.OnMessage("MRSIM_STATE_a", b.data(), b.size());
    }
    rec.Flush();
    EXPECT_FALSE(rec.failed());
    const auto stats = rec.Stats();
    ASSERT_EQ(stats.size(), 1u);
    EXPECT_EQ(stats[0].rows, 5);
    EXPECT_EQ(stats[0].files.size(), 2u);
  }
  const auto one = testing::ReadCsvFile(dir + "/MRSIM_STATE_a.csv");
  const auto two = testing::ReadCsvFile(dir + "/MRSIM_STATE_a.part2.csv");
  EXPECT_EQ(one.rows.size(), 3u);
  EXPECT_EQ(two.rows.size(), 2u);
  EXPECT_EQ(one.Column("module3.z"), -1);
  EXPECT_GE(two.Column("module3.z"), 0);
  EXPECT_EQ(two.rows[0].size(), two.header.size());
  EXPECT_TRUE(cap.Has("part2.csv"));
}

// A shape seen before goes back to its own file: a command channel where
// the camera's answers (no joints) alternate with a controller's does not
// use up the files.
TEST(LoggerRecorder, AlternatingShapesKeepOneFileEach) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_alternating");
  Capture cap;
  {
    Recorder rec(registry, cap.Options(dir));
    for (int64_t seq = 0; seq < 40; ++seq) {
      Send(rec, "MRSIM_STATE_a",
           testing::KnownRobotState(seq, seq % 2 == 0 ? 3 : 2, 0));
    }
    rec.Flush();
    const auto stats = rec.Stats();
    EXPECT_EQ(stats[0].files.size(), 2u);
    EXPECT_EQ(stats[0].rows, 40);
    EXPECT_EQ(stats[0].dropped, 0);
  }
  const auto even = testing::ReadCsvFile(dir + "/MRSIM_STATE_a.csv");
  const auto odd = testing::ReadCsvFile(dir + "/MRSIM_STATE_a.part2.csv");
  ASSERT_EQ(even.rows.size(), 20u);
  ASSERT_EQ(odd.rows.size(), 20u);
  EXPECT_EQ(even.rows[1][even.Column("seq")], "2");
  EXPECT_EQ(odd.rows[1][odd.Column("seq")], "3");
}

// A controller and mrsim-camera's lockstep answers share a command
// channel, each numbering its commands on its own: no gaps or jumps back,
// while a command one of them lost is still a gap, named by its sender.
TEST(LoggerRecorder, TwoSendersOnOneChannelEachKeepTheirOwnSeq) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_two_senders");
  Capture cap;
  Recorder rec(registry, cap.Options(dir));
  auto send = [&rec](const std::string& sender, int64_t seq, int joints) {
    joint_command_t cmd;
    cmd.seq = seq;
    cmd.robot = "snake";
    cmd.sender = sender;
    cmd.state_seq = seq;
    cmd.num_joints = joints;
    cmd.target.assign(joints, 0.1);
    std::vector<uint8_t> b(static_cast<size_t>(cmd.getEncodedSize()));
    cmd.encode(b.data(), 0, static_cast<int>(b.size()));
    rec.OnMessage("MRSIM_COMMAND_snake", b.data(), b.size());
  };
  for (int64_t k = 0; k < 20; ++k) {
    send("mrsim-lua", 100 + k, 3);
    if (k != 7) send("mrsim-camera", k, 0);  // the camera's 7th is lost
  }
  rec.Flush();
  const auto stats = rec.Stats();
  ASSERT_EQ(stats.size(), 1u);
  EXPECT_EQ(stats[0].gaps, 1);
  EXPECT_EQ(stats[0].missing, 1);
  EXPECT_EQ(stats[0].back_jumps, 0);
  EXPECT_TRUE(cap.Has("MRSIM_COMMAND_snake (sender mrsim-camera): gap: seq 7"));
}

// Traffic that decodes but changes shape with every message (a forged or
// confused sender) must not become hundreds of part files: after
// kMaxPartFiles the rows of new shapes are counted, with one warning, and
// rows of the last file's shape still go to it.
TEST(LoggerRecorder, PartFilesPerChannelAreCappedAndTheRestCountedAsDropped) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_part_cap");
  Capture cap;
  const int shapes = static_cast<int>(Recorder::kMaxPartFiles) + 20;
  {
    Recorder rec(registry, cap.Options(dir));
    for (int k = 0; k < shapes; ++k) {
      Send(rec, "MRSIM_STATE_a", testing::KnownRobotState(k, 1 + k, 0));
    }
    // The last file's shape again: written.
    Send(rec, "MRSIM_STATE_a",
         testing::KnownRobotState(shapes, Recorder::kMaxPartFiles, 0));
    rec.Flush();
    const auto stats = rec.Stats();
    ASSERT_EQ(stats.size(), 1u);
    EXPECT_EQ(stats[0].files.size(), Recorder::kMaxPartFiles);
    EXPECT_EQ(stats[0].rows, static_cast<int64_t>(Recorder::kMaxPartFiles) + 1);
    EXPECT_EQ(stats[0].dropped,
              shapes - static_cast<int64_t>(Recorder::kMaxPartFiles));
    EXPECT_NE(rec.Summary().find("dropped"), std::string::npos);
  }
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, static_cast<int>(Recorder::kMaxPartFiles));
  int warnings = 0;
  for (const std::string& l : cap.lines) {
    if (l.find("counted and dropped") != std::string::npos) ++warnings;
  }
  EXPECT_EQ(warnings, 1);
}

TEST(LoggerRecorder, ChannelsBeyondTheCapAreCountedNotRecorded) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_channel_cap");
  Capture cap;
  Recorder rec(registry, cap.Options(dir));
  const auto b = Encode(testing::KnownRobotState(0, 1, 0));
  const size_t extra = 5;
  for (size_t k = 0; k < Recorder::kMaxChannels + extra; ++k) {
    // Unknown type: counted per channel, no file, so the test stays cheap.
    const uint8_t foreign[12] = {9, 9, 9, 9, 9, 9, 9, 9, 0, 0, 0, 0};
    rec.OnMessage("X" + std::to_string(k), foreign, sizeof(foreign));
  }
  rec.OnMessage("MRSIM_STATE_late", b.data(), b.size());
  EXPECT_EQ(rec.Stats().size(), Recorder::kMaxChannels);
  EXPECT_EQ(rec.messages_on_extra_channels(), static_cast<int64_t>(extra) + 1);
  EXPECT_EQ(rec.CsvPath("MRSIM_STATE_late"), "");
  EXPECT_TRUE(cap.Has("further channels are counted and dropped"));
}

// A forged seq of INT64_MAX once made the missing count overflow into
// garbage: a jump too far to be lost messages is reported, not counted.
TEST(LoggerSeqTracker, ForgedSequenceNumbersAreNoGap) {
  SeqTracker t;
  t.Add(5);
  const SeqTracker::Event e = t.Add(std::numeric_limits<int64_t>::max());
  EXPECT_TRUE(e.jumped);
  EXPECT_EQ(e.missing, 0);
  t.Add(std::numeric_limits<int64_t>::min());
  t.Add(7);
  t.Add(9);
  EXPECT_EQ(t.missing(), 1);
  EXPECT_EQ(t.gaps(), 1);
  EXPECT_EQ(t.forward_jumps(), 2);
}

TEST(LoggerRecorder, MalformedAndForeignMessagesAreCountedNotWritten) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_malformed");
  Capture cap;
  Recorder rec(registry, cap.Options(dir));
  auto good = Encode(testing::KnownRobotState(0, 2, 0));
  rec.OnMessage("S", good.data(), good.size());
  auto cut = good;
  cut.resize(cut.size() - 3);
  rec.OnMessage("S", cut.data(), cut.size());
  const uint8_t tiny[3] = {1, 2, 3};
  rec.OnMessage("S", tiny, sizeof(tiny));
  const uint8_t foreign[12] = {9, 9, 9, 9, 9, 9, 9, 9, 0, 0, 0, 0};
  rec.OnMessage("S", foreign, sizeof(foreign));
  rec.OnMessage("U", foreign, sizeof(foreign));
  rec.Flush();
  const auto stats = rec.Stats();
  ASSERT_EQ(stats.size(), 2u);
  EXPECT_EQ(stats[0].channel, "S");
  EXPECT_EQ(stats[0].messages, 4);
  EXPECT_EQ(stats[0].rows, 1);
  EXPECT_EQ(stats[0].malformed, 2);
  EXPECT_EQ(stats[0].other_type, 1);
  EXPECT_EQ(stats[1].unknown_type, 1);
  EXPECT_FALSE(std::filesystem::exists(dir + "/U.csv"));
  EXPECT_TRUE(cap.Has("malformed"));
  EXPECT_NE(rec.Summary().find("U: 1 messages of unknown type"),
            std::string::npos)
      << rec.Summary();
}

// Traffic signed with a key (docs/security.md) is logged without the key:
// the signature trailer after the message is not taken for garbage.
TEST(LoggerRecorder, SignedMessagesAreWrittenLikeUnsignedOnes) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_signed");
  Capture cap;
  Recorder rec(registry, cap.Options(dir));
  MessageAuth auth("0123456789abcdef0123456789abcdef");
  for (int64_t seq = 0; seq < 3; ++seq) {
    const auto b = Encode(testing::KnownRobotState(seq, 2, 1));
    std::vector<uint8_t> signed_message;
    auth.Sign("MRSIM_STATE_a", b.data(), b.size(), 1000 + seq, &signed_message);
    rec.OnMessage("MRSIM_STATE_a", signed_message.data(),
                  signed_message.size());
  }
  rec.Flush();
  const auto stats = rec.Stats();
  ASSERT_EQ(stats.size(), 1u);
  EXPECT_EQ(stats[0].rows, 3);
  EXPECT_EQ(stats[0].malformed, 0);
}

// A lockstep simulator re-sends the states its controllers have not
// answered (pipelined: the two it awaits, older first); the CSV keeps one row
// per state and the log does not cry "publisher restarted".
TEST(LoggerRecorder, ResentMessagesAreWrittenOnceAndNotToldAsJumpsBack) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_resent");
  Capture cap;
  {
    Recorder rec(registry, cap.Options(dir));
    for (int64_t seq : {0, 0, 0, 1, 2, 1, 2, 3, 2, 3, 4}) {
      Send(rec, "MRSIM_STATE_a", testing::KnownRobotState(seq, 3, 1));
    }
    rec.Flush();
    const auto stats = rec.Stats();
    ASSERT_EQ(stats.size(), 1u);
    EXPECT_EQ(stats[0].messages, 11);
    EXPECT_EQ(stats[0].rows, 5);
    EXPECT_EQ(stats[0].repeats, 6);
    EXPECT_EQ(stats[0].back_jumps, 0);
    EXPECT_EQ(stats[0].gaps, 0);
    EXPECT_NE(rec.Summary().find("6 re-sends skipped"), std::string::npos)
        << rec.Summary();
  }
  EXPECT_TRUE(cap.lines.empty()) << cap.lines.front();
  const auto csv = testing::ReadCsvFile(dir + "/MRSIM_STATE_a.csv");
  const int seq_col = csv.Column("seq");
  ASSERT_GE(seq_col, 0);
  ASSERT_EQ(csv.rows.size(), 5u);
  for (size_t i = 0; i < csv.rows.size(); ++i) {
    EXPECT_EQ(csv.rows[i][seq_col], std::to_string(i));
  }
}

// A publisher that restarted sends its seq again with other content: that
// is data, written and told, not a re-send.
TEST(LoggerRecorder, ARestartedPublishersRowsAreWrittenAndTold) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("recorder_restart");
  Capture cap;
  Recorder rec(registry, cap.Options(dir));
  for (int64_t seq : {0, 1, 2}) {
    Send(rec, "S", testing::KnownRobotState(seq, 3, 1));
  }
  for (int64_t seq : {0, 1}) {
    robot_state_t m = testing::KnownRobotState(seq, 3, 1);
    m.joints[0].angle += 0.5;  // the new run moved differently
    Send(rec, "S", m);
  }
  rec.Flush();
  const auto stats = rec.Stats();
  ASSERT_EQ(stats.size(), 1u);
  EXPECT_EQ(stats[0].rows, 5);
  EXPECT_EQ(stats[0].repeats, 0);
  EXPECT_EQ(stats[0].back_jumps, 1);
  EXPECT_TRUE(cap.Has("seq went back from 2 to 0"));
}

TEST(LoggerSeq, GapsAndJumpsBackAreTold) {
  SeqTracker t;
  EXPECT_EQ(t.Add(5).missing, 0);
  EXPECT_EQ(t.Add(6).missing, 0);
  const auto gap = t.Add(9);
  EXPECT_EQ(gap.missing, 2);
  EXPECT_EQ(gap.first_missing, 7);
  const auto back = t.Add(0);
  EXPECT_TRUE(back.went_back);
  EXPECT_EQ(back.previous, 9);
  EXPECT_EQ(t.Add(1).missing, 0);
  EXPECT_EQ(t.count(), 5);
  EXPECT_EQ(t.gaps(), 1);
  EXPECT_EQ(t.missing(), 2);
  EXPECT_EQ(t.back_jumps(), 1);
}

TEST(LoggerCsvWriter, FullDiskNamesTheFileAndLaterWritesFailToo) {
  const std::string dir = testing::TempDir("csv_writer_full");
  const std::string path = dir + "/full.csv";
  std::filesystem::create_symlink("/dev/full", path);
  CsvWriter w(path);
  w.WriteLine("a,b");
  try {
    w.Flush();
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write " + path),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(w.failed());
  EXPECT_THROW(w.WriteLine("c,d"), std::runtime_error);
}

TEST(LoggerCsvWriter, EveryLineEndsWhole) {
  const std::string dir = testing::TempDir("csv_writer_lines");
  const std::string path = dir + "/a.csv";
  {
    CsvWriter w(path);
    // More than the write buffer, so some lines go out before Flush.
    const std::string line(1000, 'x');
    for (int i = 0; i < 3000; ++i) w.WriteLine(line);
    EXPECT_EQ(w.lines(), 3000);
  }
  const std::string text = testing::ReadText(path);
  EXPECT_EQ(text.size(), 3000u * 1001u);
  EXPECT_EQ(text.back(), '\n');
}

TEST(LoggerQueue, DropsAndCountsWhenFullAndDrainsAfterClose) {
  MessageQueue q(100);
  const uint8_t data[40] = {};
  EXPECT_TRUE(q.Push("A", data, 40));
  EXPECT_TRUE(q.Push("A", data, 40));
  EXPECT_FALSE(q.Push("A", data, 40));
  EXPECT_EQ(q.dropped(), 1);
  std::vector<QueuedMessage> out;
  EXPECT_TRUE(q.PopAll(&out, std::chrono::milliseconds(10)));
  EXPECT_EQ(out.size(), 2u);
  EXPECT_TRUE(q.Push("B", data, 40));
  q.Close();
  EXPECT_FALSE(q.Push("B", data, 40));
  out.clear();
  EXPECT_TRUE(q.PopAll(&out, std::chrono::milliseconds(10)));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].channel, "B");
  EXPECT_FALSE(q.PopAll(&out, std::chrono::milliseconds(10)));
}

TEST(LoggerQueue, WriterWakesOnceEnoughIsQueuedOrAtItsPeriod) {
  MessageQueue q(1000, 100);
  const uint8_t data[60] = {};
  // Below the wake level a wait ends at its timeout with what is there.
  ASSERT_TRUE(q.Push("A", data, 60));
  std::vector<QueuedMessage> out;
  EXPECT_TRUE(q.PopAll(&out, std::chrono::milliseconds(10)));
  EXPECT_EQ(out.size(), 1u);
  // Crossing the wake level ends a wait that would otherwise last an hour
  // (a missing wake-up hangs this test until ctest's timeout).
  out.clear();
  std::thread writer([&] { q.PopAll(&out, std::chrono::hours(1)); });
  ASSERT_TRUE(q.Push("A", data, 60));
  ASSERT_TRUE(q.Push("B", data, 60));
  writer.join();
  EXPECT_GE(out.size(), 1u);
  q.Close();
}

}  // namespace
}  // namespace mrsim

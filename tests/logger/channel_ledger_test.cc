#include "logger/channel_ledger.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mrsim {
namespace {

struct Ledger {
  std::vector<std::string> reports;
  ChannelLedger ledger{
      "CH", [this](const std::string& text) { reports.push_back(text); }};
};

TEST(ChannelLedger, ResendUnderTheSameSeqIsCountedNotWritten) {
  Ledger l;
  ASSERT_TRUE(l.ledger.TakeSeq(5, "a"));
  l.ledger.Remember(5, std::string_view("a"));
  EXPECT_FALSE(l.ledger.TakeSeq(5, "a"));
  // The same seq with other content is a restarted publisher: written.
  EXPECT_TRUE(l.ledger.TakeSeq(5, "b"));
  EXPECT_EQ(l.ledger.stats().repeats, 1);
  EXPECT_TRUE(l.ledger.stats().has_seq);
}

TEST(ChannelLedger, WindowForgetsTheOldestMessage) {
  Ledger l;
  for (int64_t s = 0; s <= static_cast<int64_t>(ChannelLedger::kRecentMessages);
       ++s) {
    ASSERT_TRUE(l.ledger.TakeSeq(s, "m"));
    std::string row = "m";
    l.ledger.Remember(s, &row);
  }
  EXPECT_TRUE(l.ledger.TakeSeq(0, "m"));  // out of the window: written
  EXPECT_FALSE(l.ledger.TakeSeq(ChannelLedger::kRecentMessages, "m"));
}

TEST(ChannelLedger, GapIsReportedAndCounted) {
  Ledger l;
  ASSERT_TRUE(l.ledger.TakeSeq(1, "a"));
  ASSERT_TRUE(l.ledger.TakeSeq(4, "b"));
  ASSERT_EQ(l.reports.size(), 1u);
  EXPECT_EQ(l.reports[0], "CH: gap: seq 2..3 missing (2 messages)");
  const ChannelStats s = l.ledger.Stats();
  EXPECT_EQ(s.gaps, 1);
  EXPECT_EQ(s.missing, 2);
  EXPECT_EQ(s.first_seq, 1);
  EXPECT_EQ(s.last_seq, 4);
}

TEST(ChannelLedger, WarningsStopAtTheCapWithOneLineSayingSo) {
  Ledger l;
  for (int i = 0; i < 2 * ChannelLedger::kMaxReports; ++i) {
    EXPECT_FALSE(l.ledger.CheckSize(3));
  }
  ASSERT_EQ(l.reports.size(), static_cast<size_t>(ChannelLedger::kMaxReports));
  EXPECT_EQ(l.reports.back(),
            "CH: further warnings on this channel are only counted");
  EXPECT_EQ(l.ledger.stats().malformed, 2 * ChannelLedger::kMaxReports);
}

TEST(ChannelLedger, OnlyTheFirstMessageOfAnUnknownTypeIsReported) {
  Ledger l;
  l.ledger.UnknownType(0x0102030405060708);
  l.ledger.UnknownType(0x0102030405060708);
  ASSERT_EQ(l.reports.size(), 1u);
  EXPECT_NE(l.reports[0].find("0x0102030405060708"), std::string::npos);
  EXPECT_EQ(l.ledger.stats().unknown_type, 2);
}

TEST(LcmFingerprint, ReadsTheFirstEightBytesBigEndian) {
  const uint8_t data[8] = {0x80, 0, 0, 0, 0, 0, 0, 0x01};
  EXPECT_EQ(LcmFingerprint(data), static_cast<int64_t>(0x8000000000000001ull));
}

}  // namespace
}  // namespace mrsim

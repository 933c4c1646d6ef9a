// McapWriter and McapReader: what one writes the other reads back, CRCs
// catch a changed byte, a file cut off reads up to its last whole chunk.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "logger/mcap/mcap_reader.h"
#include "logger/mcap/mcap_writer.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"

namespace mrsim::mcap {
namespace {

struct Got {
  std::string topic;
  uint32_t sequence;
  uint64_t log_time;
  std::string data;
};

std::vector<Got> ReadAll(const std::string& bytes, McapSummary* summary) {
  std::vector<Got> out;
  *summary = ReadMcap(bytes, "test.mcap", [&](const McapMessage& m) {
    out.push_back(
        {m.channel->topic, m.sequence, m.log_time, std::string(m.data)});
  });
  return out;
}

// Two channels, `n` messages each, chunks of about `chunk` bytes.
std::string WriteFile(const std::string& path, int n, size_t chunk,
                      bool finish = true,
                      ChunkCompression compression = ChunkCompression::kZstd) {
  McapWriterOptions options;
  options.chunk_size = chunk;
  options.compression = compression;
  {
    McapWriter w(path, options);
    const uint16_t schema = w.AddSchema("t", "jsonschema", "{}");
    const uint16_t a = w.AddChannel(schema, "A", "json");
    const uint16_t b = w.AddChannel(schema, "B", "json");
    for (int i = 0; i < n; ++i) {
      const std::string text = "{\"i\":" + std::to_string(i) + "}";
      w.WriteMessage(a, i, 1000 * i, 1000 * i, text);
      w.WriteMessage(b, i, 1000 * i + 1, 1000 * i + 1, text);
    }
    if (finish) {
      w.Finish();
    } else {
      w.CloseChunk();
      // A crash: the writer is never finished. Leak nothing, write nothing
      // more: the test copies the file as it is now.
      std::ifstream in(path, std::ios::binary);
      std::stringstream ss;
      ss << in.rdbuf();
      return ss.str();
    }
  }
  return testing::ReadFileText(path);
}

TEST(McapFile, WhatIsWrittenReadsBackInOrderWithItsChannelsAndTimes) {
  const std::string path = testing::TempDir("mcap_roundtrip") + "/a.mcap";
  const std::string bytes = WriteFile(path, 500, 4096);
  McapSummary summary;
  const std::vector<Got> got = ReadAll(bytes, &summary);
  ASSERT_EQ(got.size(), 1000u);
  EXPECT_TRUE(summary.complete);
  EXPECT_GT(summary.chunks, 1);
  EXPECT_EQ(summary.messages, 1000);
  ASSERT_EQ(summary.schemas.size(), 1u);
  EXPECT_EQ(summary.schemas.begin()->second.encoding, "jsonschema");
  for (int i = 0; i < 500; ++i) {
    EXPECT_EQ(got[2 * i].topic, "A");
    EXPECT_EQ(got[2 * i + 1].topic, "B");
    EXPECT_EQ(got[2 * i].sequence, static_cast<uint32_t>(i));
    EXPECT_EQ(got[2 * i + 1].log_time, 1000u * i + 1);
    EXPECT_EQ(got[2 * i].data, "{\"i\":" + std::to_string(i) + "}");
  }
  // Starts and ends with the magic.
  EXPECT_EQ(bytes.compare(0, 8, std::string(kMagic, 8)), 0);
  EXPECT_EQ(bytes.compare(bytes.size() - 8, 8, std::string(kMagic, 8)), 0);
}

TEST(McapFile, AFileCutAnywhereReadsItsWholeChunksAndSaysItIsIncomplete) {
  const std::string path = testing::TempDir("mcap_cut") + "/a.mcap";
  const std::string bytes = WriteFile(path, 300, 2048, /*finish=*/false);
  McapSummary whole_summary;
  const size_t whole = ReadAll(bytes, &whole_summary).size();
  EXPECT_EQ(whole, 600u);
  EXPECT_FALSE(whole_summary.complete);
  size_t previous = 0;
  for (size_t cut = 8; cut <= bytes.size(); cut += 97) {
    McapSummary summary;
    const std::vector<Got> got = ReadAll(bytes.substr(0, cut), &summary);
    EXPECT_FALSE(summary.complete);
    EXPECT_GE(got.size(), previous) << "cut at " << cut;
    previous = got.size();
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].sequence, i / 2) << "cut at " << cut;
    }
  }
}

TEST(McapFile, AChangedByteInAChunkOrTheSummaryIsRefusedNamingItsOffset) {
  const std::string path = testing::TempDir("mcap_crc") + "/a.mcap";
  const std::string bytes = WriteFile(path, 200, 1 << 20);
  McapSummary summary;
  // In the chunk's compressed bytes (past magic, header, chunk fields).
  std::string bad = bytes;
  bad[200] = static_cast<char>(bad[200] ^ 0x40);
  EXPECT_THROW(ReadAll(bad, &summary), McapError);
  // In the summary (the statistics, just before the footer's records).
  bad = bytes;
  const size_t at = bytes.size() - 8 - 29 - 60;
  bad[at] = static_cast<char>(bad[at] ^ 0x01);
  try {
    ReadAll(bad, &summary);
    ADD_FAILURE() << "a changed summary byte was not noticed";
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find("test.mcap: byte "), std::string::npos)
        << e.what();
  }
}

TEST(McapFile, UncompressedChunksReadBackWholeOrCutAndAreCrcChecked) {
  const std::string path = testing::TempDir("mcap_none") + "/a.mcap";
  const std::string bytes =
      WriteFile(path, 300, 2048, true, ChunkCompression::kNone);
  // The records are in the file as they are, and the chunks say so.
  EXPECT_NE(bytes.find("{\"i\":299}"), std::string::npos);
  EXPECT_EQ(bytes.find("zstd"), std::string::npos);
  McapSummary summary;
  const std::vector<Got> got = ReadAll(bytes, &summary);
  ASSERT_EQ(got.size(), 600u);
  EXPECT_TRUE(summary.complete);
  EXPECT_GT(summary.chunks, 1);
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].sequence, i / 2);
    EXPECT_EQ(got[i].data, "{\"i\":" + std::to_string(i / 2) + "}");
  }
  // A changed digit in a message is caught by its chunk's CRC.
  std::string bad = bytes;
  const size_t digit = bytes.find("{\"i\":123}") + 5;
  bad[digit] = '4';
  EXPECT_THROW(ReadAll(bad, &summary), McapError);
  // Cut anywhere (a killed writer): its whole chunks, in order.
  const std::string unfinished =
      WriteFile(path, 300, 2048, false, ChunkCompression::kNone);
  size_t previous = 0;
  for (size_t cut = 8; cut <= unfinished.size(); cut += 97) {
    McapSummary cut_summary;
    const std::vector<Got> some =
        ReadAll(unfinished.substr(0, cut), &cut_summary);
    EXPECT_FALSE(cut_summary.complete);
    EXPECT_GE(some.size(), previous) << "cut at " << cut;
    previous = some.size();
    for (size_t i = 0; i < some.size(); ++i) {
      EXPECT_EQ(some[i].sequence, i / 2) << "cut at " << cut;
    }
  }
  EXPECT_EQ(previous, 600u);
}

TEST(McapFile, ForgedLengthsAreRefusedBeforeAnythingIsAllocated) {
  const std::string path = testing::TempDir("mcap_forged") + "/a.mcap";
  const std::string bytes = WriteFile(path, 10, 1 << 20);
  // The chunk's uncompressed size (after its two times) says 2^40 bytes.
  const size_t chunk = bytes.find('\x06', 8 + 9);
  ASSERT_NE(chunk, std::string::npos);
  std::string bad = bytes;
  const uint64_t huge = uint64_t{1} << 40;
  std::memcpy(&bad[chunk + 9 + 16], &huge, 8);
  McapSummary summary;
  try {
    ReadAll(bad, &summary);
    ADD_FAILURE() << "a chunk of 1 TiB was accepted";
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find("over"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(ReadAll("not an mcap file", &summary), McapError);
}

TEST(McapFile, AFailedWriteLeavesTheFileReadableToItsLastWholeChunk) {
  const std::string path = testing::TempDir("mcap_full") + "/a.mcap";
  McapWriterOptions options;
  options.chunk_size = 1 << 20;
  McapWriter w(path, options);
  const uint16_t channel =
      w.AddChannel(w.AddSchema("t", "jsonschema", "{}"), "A", "json");
  // A disk that fills at 20 kB: writes past it fail (EFBIG, SIGXFSZ
  // ignored), the first one part-way through a chunk.
  signal(SIGXFSZ, SIG_IGN);
  rlimit old{};
  getrlimit(RLIMIT_FSIZE, &old);
  rlimit small = old;
  small.rlim_cur = 20000;
  setrlimit(RLIMIT_FSIZE, &small);
  std::string error;
  for (int i = 0; i < 10000 && error.empty(); ++i) {
    std::string text = "{\"i\":" + std::to_string(i) + ",\"pad\":\"";
    for (int k = 0; k < 40; ++k) text += std::to_string(i * 7919 + k);
    text += "\"}";
    try {
      w.WriteMessage(channel, i, i, i, text);
      if (i % 20 == 19) w.CloseChunk();
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
  }
  EXPECT_THROW(w.Finish(), std::runtime_error);
  setrlimit(RLIMIT_FSIZE, &old);
  signal(SIGXFSZ, SIG_DFL);
  EXPECT_NE(error.find("cannot write " + path), std::string::npos) << error;
  McapSummary summary;
  const std::vector<Got> got = ReadAll(testing::ReadFileText(path), &summary);
  EXPECT_FALSE(summary.complete);
  EXPECT_GT(got.size(), 0u);
  EXPECT_EQ(got.size() % 20, 0u);  // whole chunks only
}

}  // namespace
}  // namespace mrsim::mcap

#include <gtest/gtest.h>

#include "optimizer/farm/payload_chunks.h"

namespace mrsim {
namespace {

TEST(FarmChunks, ReassemblesOutOfOrderWithRepeatsAndReportsMissing) {
  std::string payload;
  for (int i = 0; i < 10000; ++i) payload += static_cast<char>(i * 7 % 251);
  const std::vector<std::string> chunks = SplitPayload(payload, 999);
  ASSERT_EQ(chunks.size(), 11u);
  for (const std::string& c : chunks) EXPECT_LE(c.size(), 999u);
  ChunkAssembler a(static_cast<int>(chunks.size()),
                   static_cast<long long>(payload.size()));
  for (int i = 10; i >= 0; i -= 2) ASSERT_TRUE(a.Add(i, chunks[i]));
  EXPECT_FALSE(a.complete());
  EXPECT_EQ(a.Missing(3), (std::vector<int>{1, 3, 5}));
  EXPECT_TRUE(a.Add(4, chunks[4]));  // a repeat changes nothing
  EXPECT_FALSE(a.Add(11, chunks[0]));
  EXPECT_FALSE(a.Add(-1, chunks[0]));
  for (int i = 1; i < 11; i += 2) ASSERT_TRUE(a.Add(i, chunks[i]));
  ASSERT_TRUE(a.complete());
  EXPECT_TRUE(a.Missing(10).empty());
  EXPECT_EQ(a.Join(), payload);
}

}  // namespace
}  // namespace mrsim

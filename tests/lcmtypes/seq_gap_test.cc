// Lost-message counts from sequence numbers that may be forged.
#include "lcmtypes/runtime/seq_gap.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace mrsim {
namespace {

constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
constexpr int64_t kMin = std::numeric_limits<int64_t>::min();

TEST(SeqGap, CountsTheMessagesBetweenTwoNearbyNumbers) {
  EXPECT_EQ(SeqGap(5, 6), 0);
  EXPECT_EQ(SeqGap(5, 9), 3);
  EXPECT_EQ(SeqGap(-1, 1), 1);
  EXPECT_EQ(SeqGap(0, kMaxSeqGap + 1), kMaxSeqGap);
}

TEST(SeqGap, ForgedOrRestartedNumbersAreNoGapAndNeverOverflow) {
  EXPECT_EQ(SeqGap(9, 5), 0);
  EXPECT_EQ(SeqGap(0, kMaxSeqGap + 2), 0);
  EXPECT_EQ(SeqGap(kMin, kMax), 0);
  EXPECT_EQ(SeqGap(-5, kMax), 0);
  EXPECT_EQ(SeqGap(kMax, kMin), 0);
  EXPECT_EQ(SeqGap(kMax - 3, kMax), 2);
}

TEST(SeqGap, FarBehindNeverOverflows) {
  EXPECT_TRUE(SeqFarBehind(5000, 10, 1000));
  EXPECT_FALSE(SeqFarBehind(500, 10, 1000));
  EXPECT_FALSE(SeqFarBehind(10, 5000, 1000));
  EXPECT_TRUE(SeqFarBehind(kMax, kMin, 1000));
  EXPECT_FALSE(SeqFarBehind(kMin, kMax, 1000));
}

}  // namespace
}  // namespace mrsim

// Numbers in the files mrsim resumes from read back bit for bit, and only
// when the whole text is a number.
#include "common/exact_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace mrsim {
namespace {

TEST(ExactNumber, EveryDoubleReadsBackBitForBit) {
  for (double v : {0.0, -0.0, 0.1, 1.0 / 3.0, -2.5e-300, 6.02214076e23,
                   std::numeric_limits<double>::denorm_min(),
                   std::numeric_limits<double>::max(),
                   std::numeric_limits<double>::infinity()}) {
    const std::optional<double> back = ParseWholeNumber(ExactNumber(v));
    ASSERT_TRUE(back.has_value()) << ExactNumber(v);
    EXPECT_EQ(std::memcmp(&v, &*back, sizeof(double)), 0) << ExactNumber(v);
  }
}

TEST(ExactNumber, OnlyTheWholeTextIsANumber) {
  EXPECT_EQ(ParseWholeNumber("2.5"), 2.5);
  EXPECT_EQ(ParseWholeNumber("0x1.8p+1"), 3.0);
  for (const char* bad : {"", " ", "1.0s", "1,0", "0x1.0pq", "abc", "1 2"}) {
    EXPECT_FALSE(ParseWholeNumber(bad).has_value()) << "'" << bad << "'";
  }
}

}  // namespace
}  // namespace mrsim

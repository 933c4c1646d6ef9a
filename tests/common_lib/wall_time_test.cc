#include "common/wall_time.h"

#include <gtest/gtest.h>

#include "common/version.h"

namespace mrsim {
namespace {

TEST(WallTime, SecondsOfAnyDuration) {
  EXPECT_DOUBLE_EQ(Seconds(std::chrono::milliseconds(1500)), 1.5);
  EXPECT_DOUBLE_EQ(Seconds(std::chrono::microseconds(-250)), -0.00025);
}

TEST(WallTime, WallMicrosIsTheUnixTimeInMicroseconds) {
  const auto before = std::chrono::system_clock::now();
  const std::int64_t t = WallMicros();
  const auto after = std::chrono::system_clock::now();
  auto micros = [](auto tp) {
    return std::chrono::duration_cast<std::chrono::microseconds>(
               tp.time_since_epoch())
        .count();
  };
  EXPECT_LE(micros(before), t);
  EXPECT_GE(micros(after), t);
}

TEST(Version, IsTheProjectVersion) {
  EXPECT_STREQ(kVersion, MRSIM_PROJECT_VERSION);
}

}  // namespace
}  // namespace mrsim

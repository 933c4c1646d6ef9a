// A video recorded from the window is as long as the recording lasted,
// whatever rate the window draws at.
#include "studio/live/video_clock.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace mrsim::studio {
namespace {

TEST(VideoClock, SlowWindowRepeatsFramesToKeepTheLength) {
  VideoClock clock(30);
  EXPECT_EQ(clock.FramesDue(0), 1);
  // A window drawing at 5 frames/s for 3 s.
  int64_t written = 1;
  for (int i = 1; i <= 15; ++i) written += clock.FramesDue(i * 0.2);
  EXPECT_EQ(written, 91);  // frames 0..90: 3 s at 30 frames/s
  EXPECT_NEAR(clock.seconds(), 3.0, 1.0 / 30 + 1e-9);
}

TEST(VideoClock, FastWindowSkipsPictures) {
  VideoClock clock(30);
  int64_t written = 0;
  for (int i = 0; i <= 360; ++i) written += clock.FramesDue(i / 120.0);
  EXPECT_EQ(written, 91);
  EXPECT_EQ(clock.frames(), 91);
}

TEST(VideoClock, ClockGoingBackAddsNothing) {
  VideoClock clock(25);
  EXPECT_EQ(clock.FramesDue(1.0), 26);
  EXPECT_EQ(clock.FramesDue(0.5), 0);
  EXPECT_EQ(clock.FramesDue(-3), 0);
}

TEST(VideoClock, RefusesRatesOutOfRange) {
  EXPECT_THROW(VideoClock(0), std::invalid_argument);
  EXPECT_THROW(VideoClock(-1), std::invalid_argument);
  EXPECT_THROW(VideoClock(1000), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim::studio

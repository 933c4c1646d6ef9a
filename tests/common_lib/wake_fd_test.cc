#include "common/wake_fd.h"

#include <gtest/gtest.h>
#include <poll.h>

#include <thread>

namespace mrsim {
namespace {

bool Readable(const WakeFd& w, int timeout_ms) {
  pollfd p{w.fd(), POLLIN, 0};
  return poll(&p, 1, timeout_ms) == 1 && (p.revents & POLLIN);
}

TEST(WakeFd, SignalFromAnotherThreadEndsAPollUntilDrained) {
  WakeFd wake;
  EXPECT_FALSE(Readable(wake, 0));
  EXPECT_FALSE(wake.Drain());
  std::thread other([&] {
    wake.Signal();
    wake.Signal();  // twice: still one wake-up
  });
  EXPECT_TRUE(Readable(wake, 30000));
  other.join();
  EXPECT_TRUE(wake.Drain());
  EXPECT_FALSE(Readable(wake, 0));
}

}  // namespace
}  // namespace mrsim

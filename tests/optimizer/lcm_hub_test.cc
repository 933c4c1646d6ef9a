// mrsim-opt --hub: LCM's TCP hub is up (it accepts connections) when
// LcmHub returns, gone when it is destroyed, and a port already taken is
// refused with a message that says so.
#include "optimizer/slurm/lcm_hub.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/command_output.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"

namespace mrsim {
namespace {

int HubPort() {
  const char* offset = std::getenv("MRSIM_TEST_PORT_OFFSET");
  return 7745 + (offset != nullptr ? std::atoi(offset) : 0);
}

TEST(LcmHub, AcceptsConnectionsOnceStartedAndStopsWithItsOwner) {
  if (FindOnPath("java").empty() || !std::filesystem::exists(LcmHub::kJar)) {
    GTEST_SKIP() << "no java or " << LcmHub::kJar;
  }
  const std::string dir = testing::TempDir("lcm_hub");
  const int port = HubPort();
  {
    LcmHub hub(port, dir + "/hub.log");
    EXPECT_TRUE(TcpPortAccepts(port));
    try {
      LcmHub second(port, dir + "/hub2.log");
      FAIL() << "a second hub on the same port started";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("already listens"),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_TRUE(testing::WaitUntil([&] { return !TcpPortAccepts(port); }, 10.0));
}

}  // namespace
}  // namespace mrsim

#include "common/lcm_url.h"

#include <gtest/gtest.h>
#include <stdlib.h>

namespace mrsim {
namespace {

TEST(LcmUrl, MulticastUrlsGetTheReceiveBufferAppended) {
  EXPECT_EQ(LcmUrlWithReceiveBuffer("udpm://239.255.76.67:7667?ttl=1", 4096),
            "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=4096");
  EXPECT_EQ(LcmUrlWithReceiveBuffer("udpm://239.255.76.67:7667", 4096),
            "udpm://239.255.76.67:7667?recv_buf_size=4096");
  EXPECT_EQ(LcmUrlWithReceiveBuffer("mpudpm://239.255.76.67:7667?ttl=1", 8),
            "mpudpm://239.255.76.67:7667?ttl=1&recv_buf_size=8");
}

TEST(LcmUrl, ANamedSizeOtherTransportsAndNoSizeAreLeftAlone) {
  EXPECT_EQ(LcmUrlWithReceiveBuffer("udpm://x:1?recv_buf_size=5", 100),
            "udpm://x:1?recv_buf_size=5");
  EXPECT_EQ(LcmUrlWithReceiveBuffer("tcpq://127.0.0.1:7700", 100),
            "tcpq://127.0.0.1:7700");
  EXPECT_EQ(LcmUrlWithReceiveBuffer("memq://", 100), "memq://");
  EXPECT_EQ(LcmUrlWithReceiveBuffer("udpm://x:1", 0), "udpm://x:1");
}

TEST(LcmUrl, AnEmptyUrlIsLcmsDefault) {
  const char* saved = getenv("LCM_DEFAULT_URL");
  const std::string keep = saved ? saved : "";
  unsetenv("LCM_DEFAULT_URL");
  EXPECT_EQ(ResolveLcmUrl(""), "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(LcmUrlWithReceiveBuffer("", 64),
            "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=64");
  setenv("LCM_DEFAULT_URL", "tcpq://127.0.0.1:7701", 1);
  EXPECT_EQ(ResolveLcmUrl(""), "tcpq://127.0.0.1:7701");
  if (saved) {
    setenv("LCM_DEFAULT_URL", keep.c_str(), 1);
  } else {
    unsetenv("LCM_DEFAULT_URL");
  }
}

TEST(LcmUrl, KernelReceiveBufferMaxIsReadFromProc) {
  // Linux always has net.core.rmem_max; it is at least a few KB.
  EXPECT_GT(KernelReceiveBufferMax(), 4096);
}

// A program that cannot open LCM says how to fix it, whatever it is.
TEST(LcmUrl, CannotOpenSaysHowToFixTheRouteOrTheHub) {
  const std::string udpm = CannotOpenLcm("udpm://239.255.76.99:7667?ttl=0");
  EXPECT_NE(udpm.find("cannot open LCM at 'udpm://239.255.76.99:7667?ttl=0'"),
            std::string::npos)
      << udpm;
  EXPECT_NE(udpm.find("sudo ip route add 239.255.0.0/16 dev lo"),
            std::string::npos)
      << udpm;
  EXPECT_NE(udpm.find("ip route get 239.255.76.99`"), std::string::npos)
      << udpm;
  const std::string tcpq = CannotOpenLcm("tcpq://10.1.2.3:7700");
  EXPECT_NE(tcpq.find("hub"), std::string::npos) << tcpq;
  EXPECT_EQ(tcpq.find("ip route"), std::string::npos) << tcpq;
  EXPECT_EQ(CannotOpenLcm("memq://"), "cannot open LCM at 'memq://'");
}

}  // namespace
}  // namespace mrsim

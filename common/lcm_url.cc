#include "common/lcm_url.h"

#include <cstdlib>
#include <fstream>

namespace mrsim {

std::string ResolveLcmUrl(const std::string& url) {
  if (!url.empty()) return url;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  return env != nullptr && *env ? env : "udpm://239.255.76.67:7667?ttl=0";
}

std::string LcmUrlWithReceiveBuffer(const std::string& url,
                                    std::int64_t bytes) {
  const std::string u = ResolveLcmUrl(url);
  const bool multicast =
      u.rfind("udpm://", 0) == 0 || u.rfind("mpudpm://", 0) == 0;
  if (!multicast || bytes <= 0 ||
      u.find("recv_buf_size=") != std::string::npos) {
    return u;
  }
  return u + (u.find('?') == std::string::npos ? "?" : "&") +
         "recv_buf_size=" + std::to_string(bytes);
}

std::string CannotOpenLcm(const std::string& url) {
  const std::string u = ResolveLcmUrl(url);
  std::string text = "cannot open LCM at '" + u + "'";
  const bool multicast =
      u.rfind("udpm://", 0) == 0 || u.rfind("mpudpm://", 0) == 0;
  if (multicast) {
    // The group, for the check: udpm://GROUP:PORT?...
    const size_t start = u.find("://") + 3;
    const std::string group =
        u.substr(start, u.find_first_of(":?", start) - start);
    return text +
           " (is the URL right? multicast also needs a route on this "
           "machine, and there is none when no network is up: add one on "
           "loopback with `sudo ip link set lo multicast on && sudo ip route "
           "add 239.255.0.0/16 dev lo`, check with `ip route get " +
           group + "`)";
  }
  if (u.rfind("tcpq://", 0) == 0) {
    return text +
           " (is LCM's hub running there? `java -cp "
           "/usr/share/java/lcm.jar lcm.lcm.TCPService PORT`, or <hub> in a "
           "launch file: docs/launch.md)";
  }
  return text;
}

std::int64_t KernelReceiveBufferMax() {
  std::ifstream f("/proc/sys/net/core/rmem_max");
  std::int64_t bytes = 0;
  if (!(f >> bytes) || bytes < 0) return 0;
  return bytes;
}

}  // namespace mrsim

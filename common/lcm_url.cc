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

std::int64_t KernelReceiveBufferMax() {
  std::ifstream f("/proc/sys/net/core/rmem_max");
  std::int64_t bytes = 0;
  if (!(f >> bytes) || bytes < 0) return 0;
  return bytes;
}

}  // namespace mrsim

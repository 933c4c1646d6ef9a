#include "foxglove/control_access.h"

#include "lcmtypes/runtime/message_key.h"

namespace mrsim::foxglove {
namespace {

// Compares in time independent of where the first difference is.
bool SameSecret(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    diff |= static_cast<unsigned char>(a[k] ^ b[k]);
  }
  return diff == 0;
}

}  // namespace

std::string ControlTokenFromKeyFile(const std::string& path) {
  const std::string key = ReadKeyFile(path);
  static const char* const kHex = "0123456789abcdef";
  std::string hex;
  for (const char c : key) {
    hex.push_back(kHex[static_cast<unsigned char>(c) >> 4]);
    hex.push_back(kHex[static_cast<unsigned char>(c) & 15]);
  }
  return hex;
}

bool MayControl(bool from_loopback, std::string_view query,
                const std::string& token) {
  if (token.empty()) return from_loopback;
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view part = query.substr(0, amp);
    if (part.rfind("token=", 0) == 0 && SameSecret(part.substr(6), token)) {
      return true;
    }
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return false;
}

}  // namespace mrsim::foxglove

// FNV-1a 64: a stable content hash (scenario payloads, checkpoint
// fingerprints, exported asset names); not for security.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace mrsim {

inline std::uint64_t Fnv1a64(const void* data, std::size_t size,
                             std::uint64_t h = 14695981039346656037ull) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

inline std::uint64_t Fnv1a64(const std::string& s) {
  return Fnv1a64(s.data(), s.size());
}

inline std::string HashHex(std::uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx",
                static_cast<unsigned long long>(h));
  return text;
}

}  // namespace mrsim

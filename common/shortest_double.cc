#include "common/shortest_double.h"

// Dragonbox with its full table of powers: about 15% faster per number
// than the compressed table libfmt.so is built with, same digits. Only
// this file compiles fmt's functions itself (header-only, so every one is
// inline and links beside libfmt.so without clashing).
#define FMT_HEADER_ONLY
#define FMT_USE_FULL_CACHE_DRAGONBOX 1
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace mrsim {

namespace {

constexpr char kPairs[] =
    "0001020304050607080910111213141516171819"
    "2021222324252627282930313233343536373839"
    "4041424344454647484950515253545556575859"
    "6061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Exactly four / eight digits, zero-padded: 32-bit arithmetic, and the
// halves do not wait on each other.
inline void Write4(std::uint32_t v, char* p) {
  std::memcpy(p, kPairs + (v / 100) * 2, 2);
  std::memcpy(p + 2, kPairs + (v % 100) * 2, 2);
}
inline void Write8(std::uint32_t v, char* p) {
  Write4(v / 10000, p);
  Write4(v % 10000, p + 4);
}

// The decimal digits of v (0 < v < 10^17, as for every shortest double) at
// buf[0..17) zero-padded; returns the first significant digit.
inline const char* WriteDigits(std::uint64_t v, char* buf) {
  const std::uint64_t high = v / 100000000;
  buf[0] = static_cast<char>('0' + high / 100000000);
  Write8(static_cast<std::uint32_t>(high % 100000000), buf + 1);
  Write8(static_cast<std::uint32_t>(v % 100000000), buf + 9);
  const char* first = buf;
  while (*first == '0') ++first;
  return first;
}

}  // namespace

// The shortest digits that read back to the same double come from fmt's
// Dragonbox (about twice as fast as the Ryu inside libstdc++'s to_chars,
// which was a fifth of mrsim-log's CPU); the layout is std::to_chars's:
// fixed or scientific, whichever is shorter, fixed on a tie, exponent of at
// least two digits. Zeros, infinities, NaN and whole numbers with
// trailing zeros go to std::to_chars. Tested
// against std::to_chars on millions of values.
char* WriteDouble(double v, char* p) {
  if (v == 0 || !std::isfinite(v)) {
    return std::to_chars(p, p + kMaxDoubleChars, v).ptr;
  }
  const auto dec = fmt::detail::dragonbox::to_decimal(std::fabs(v));
  char digits_buf[17];
  const char* digits = WriteDigits(dec.significand, digits_buf);
  const int n = static_cast<int>(digits_buf + sizeof(digits_buf) - digits);
  const int k = dec.exponent;  // value = digits x 10^k
  const int sci_exp = n - 1 + k;
  const int abs_exp = sci_exp < 0 ? -sci_exp : sci_exp;
  const int sci_len = n + (n > 1 ? 1 : 0) + 2 + (abs_exp >= 100 ? 3 : 2);
  const int fixed_len = k >= 0 ? n + k : (n + k > 0 ? n + 1 : 2 - k);
  if (fixed_len <= sci_len && k > 0) {
    // An integer with trailing zeros: to_chars writes its exact digits
    // (218424378994422976, not ...980), which Dragonbox does not give.
    return std::to_chars(p, p + kMaxDoubleChars, v).ptr;
  }
  // The chosen form is at most 25 characters.
  if (v < 0) *p++ = '-';
  if (fixed_len <= sci_len) {
    if (k == 0) {
      std::memcpy(p, digits, n);
      p += n;
    } else if (n + k > 0) {
      std::memcpy(p, digits, n + k);
      p += n + k;
      *p++ = '.';
      std::memcpy(p, digits + n + k, -k);
      p += -k;
    } else {
      *p++ = '0';
      *p++ = '.';
      std::memset(p, '0', -(n + k));
      p += -(n + k);
      std::memcpy(p, digits, n);
      p += n;
    }
  } else {
    *p++ = digits[0];
    if (n > 1) {
      *p++ = '.';
      std::memcpy(p, digits + 1, n - 1);
      p += n - 1;
    }
    *p++ = 'e';
    *p++ = sci_exp < 0 ? '-' : '+';
    if (abs_exp >= 100) *p++ = static_cast<char>('0' + abs_exp / 100);
    *p++ = static_cast<char>('0' + abs_exp / 10 % 10);
    *p++ = static_cast<char>('0' + abs_exp % 10);
  }
  return p;
}

}  // namespace mrsim

#include "lcmtypes/json/json_writer.h"

#include <cmath>

#include "common/shortest_double.h"

namespace mrsim {
namespace {

// Length of the valid UTF-8 sequence at p (1-4), or 0 when it is not one
// (a stray continuation byte, an overlong form, a surrogate, past U+10FFFF
// or cut off by the end).
size_t Utf8Length(const unsigned char* p, const unsigned char* end) {
  const unsigned char c = p[0];
  size_t n = 0;
  uint32_t min = 0;
  uint32_t v = 0;
  if (c < 0x80) return 1;
  if ((c & 0xE0) == 0xC0) {
    n = 2, min = 0x80, v = c & 0x1F;
  } else if ((c & 0xF0) == 0xE0) {
    n = 3, min = 0x800, v = c & 0x0F;
  } else if ((c & 0xF8) == 0xF0) {
    n = 4, min = 0x10000, v = c & 0x07;
  } else {
    return 0;
  }
  if (static_cast<size_t>(end - p) < n) return 0;
  for (size_t i = 1; i < n; ++i) {
    if ((p[i] & 0xC0) != 0x80) return 0;
    v = (v << 6) | (p[i] & 0x3F);
  }
  if (v < min || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) return 0;
  return n;
}

}  // namespace

void JsonWriter::Double(double v) {
  if (!std::isfinite(v)) {
    Raw("null");
    return;
  }
  // The shortest text that reads back to v, as the CSV logger writes it,
  // in a form JSON accepts ("0.1", "1e-05", "-0", "3").
  char* p = Make(kMaxDoubleChars);
  size_ = static_cast<size_t>(WriteDouble(v, p) - buf_.data());
}

void JsonWriter::String(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  // Worst case: every byte becomes \u00XX (6) or U+FFFD (\ufffd, 6).
  char* p = Make(text.size() * 6 + 2);
  char* const start = p;
  *p++ = '"';
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const auto* end = s + text.size();
  while (s < end) {
    const unsigned char c = *s;
    if (c == '"' || c == '\\') {
      *p++ = '\\';
      *p++ = static_cast<char>(c);
      ++s;
    } else if (c < 0x20) {
      std::memcpy(p, "\\u00", 4);
      p[4] = kHex[c >> 4];
      p[5] = kHex[c & 15];
      p += 6;
      ++s;
    } else if (c < 0x80) {
      *p++ = static_cast<char>(c);
      ++s;
    } else {
      const size_t n = Utf8Length(s, end);
      if (n == 0) {
        std::memcpy(p, "\\ufffd", 6);
        p += 6;
        ++s;
      } else {
        std::memcpy(p, s, n);
        p += n;
        s += n;
      }
    }
  }
  *p++ = '"';
  size_ += static_cast<size_t>(p - start);
}

}  // namespace mrsim

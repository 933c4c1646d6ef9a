#include "sim_core/mesh/base64.h"

#include <glib.h>

#include <memory>
#include <stdexcept>

namespace mrsim {
namespace {

bool IsSymbol(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
         (c >= '0' && c <= '9') || c == '+' || c == '/';
}

bool IsSpace(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

struct GFreeDeleter {
  void operator()(void* p) const { g_free(p); }
};

}  // namespace

std::string Base64Encode(const std::vector<unsigned char>& bytes) {
  std::unique_ptr<gchar, GFreeDeleter> text(
      g_base64_encode(bytes.data(), bytes.size()));
  return text.get();
}

// glib decodes leniently (it skips what is not in the alphabet), so the
// input is checked here first: a damaged file must be an error naming the
// position, never silently different bytes.
std::vector<unsigned char> Base64Decode(const std::string& text) {
  std::string clean;
  clean.reserve(text.size());
  int padding = 0;
  for (size_t pos = 0; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (IsSpace(c)) continue;
    if (c == '=') {
      if (++padding > 2) {
        throw std::invalid_argument("base64: too much padding at position " +
                                    std::to_string(pos));
      }
    } else if (!IsSymbol(c) || padding > 0) {
      throw std::invalid_argument(
          std::string("base64: unexpected character '") + c + "' at position " +
          std::to_string(pos));
    }
    clean += c;
  }
  const size_t symbols = clean.size() - padding;
  if (symbols % 4 == 1) {
    throw std::invalid_argument("base64: truncated input (" +
                                std::to_string(symbols) + " symbols)");
  }
  if (padding > 0 && clean.size() % 4 != 0) {
    throw std::invalid_argument("base64: wrong padding");
  }
  while (clean.size() % 4 != 0) clean += '=';  // unpadded input is accepted
  gsize length = 0;
  std::unique_ptr<guchar, GFreeDeleter> bytes(
      g_base64_decode(clean.c_str(), &length));
  return std::vector<unsigned char>(bytes.get(), bytes.get() + length);
}

}  // namespace mrsim

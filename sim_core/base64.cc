#include "sim_core/base64.h"

#include <stdexcept>

namespace mrsim {
namespace {

constexpr char kAlphabet[] =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

bool IsSpace(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

}  // namespace

std::string Base64Encode(const std::vector<unsigned char>& bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  const size_t rest = bytes.size() - i;
  if (rest == 1) {
    const unsigned v = bytes[i] << 16;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += "==";
  } else if (rest == 2) {
    const unsigned v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

std::vector<unsigned char> Base64Decode(const std::string& text) {
  std::vector<unsigned char> out;
  out.reserve(text.size() / 4 * 3);
  unsigned acc = 0;
  int bits = 0;
  int symbols = 0;  // non-padding symbols seen
  int padding = 0;
  for (size_t pos = 0; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (IsSpace(c)) continue;
    if (c == '=') {
      ++padding;
      if (padding > 2) {
        throw std::invalid_argument("base64: too much padding at position " +
                                    std::to_string(pos));
      }
      continue;
    }
    const int v = Value(c);
    if (v < 0 || padding > 0) {
      throw std::invalid_argument(
          std::string("base64: unexpected character '") + c + "' at position " +
          std::to_string(pos));
    }
    ++symbols;
    acc = (acc << 6) | static_cast<unsigned>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xFF));
    }
  }
  const int tail = symbols % 4;
  if (tail == 1) {
    throw std::invalid_argument("base64: truncated input (" +
                                std::to_string(symbols) + " symbols)");
  }
  if (padding > 0 && (symbols + padding) % 4 != 0) {
    throw std::invalid_argument("base64: wrong padding");
  }
  // Leftover bits must be zero for canonical input.
  if (bits > 0 && (acc & ((1u << bits) - 1)) != 0) {
    throw std::invalid_argument("base64: non-zero trailing bits");
  }
  return out;
}

}  // namespace mrsim

// Appends JSON text to a buffer, fast: the generated message writers
// (mrsim/message_json.hpp) put a message's structure as literal text and
// call these for the values. Numbers are the shortest text that reads back
// to the same value; NaN and the infinities, which JSON cannot hold, are
// null; strings are escaped and made valid UTF-8 (a byte that is not
// becomes U+FFFD), since a message's strings come from the wire.
#pragma once

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace mrsim {

class JsonWriter {
 public:
  // Forgets the text, keeping the buffer's room.
  void Clear() { size_ = 0; }
  std::string_view view() const { return {buf_.data(), size_}; }
  size_t size() const { return size_; }

  void Raw(std::string_view text) {
    char* p = Make(text.size());
    std::memcpy(p, text.data(), text.size());
    size_ += text.size();
  }
  void Int(int64_t v) {
    char* p = Make(24);
    size_ = static_cast<size_t>(std::to_chars(p, p + 24, v).ptr - buf_.data());
  }
  void Bool(bool v) { Raw(v ? std::string_view("true") : "false"); }
  void Double(double v);
  void String(std::string_view text);

 private:
  char* Make(size_t n) {
    if (size_ + n > buf_.size()) {
      buf_.resize(std::max(buf_.size() * 2, size_ + n + 4096));
    }
    return buf_.data() + size_;
  }

  std::string buf_;
  size_t size_ = 0;
};

}  // namespace mrsim

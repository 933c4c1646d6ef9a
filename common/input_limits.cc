#include "common/input_limits.h"

#include <sys/stat.h>

#include <cstdio>
#include <memory>

namespace mrsim {

InputLimitError::InputLimitError(const std::string& file, int line,
                                 const std::string& what)
    : std::runtime_error(line > 0
                             ? file + ":" + std::to_string(line) + ": " + what
                             : file + ": " + what),
      line_(line) {}

namespace {

std::string Bytes(size_t n) {
  if (n >= (size_t{1} << 20) && n % (size_t{1} << 20) == 0) {
    return std::to_string(n >> 20) + " MiB";
  }
  if (n >= (size_t{1} << 10) && n % (size_t{1} << 10) == 0) {
    return std::to_string(n >> 10) + " KiB";
  }
  return std::to_string(n) + " bytes";
}

// A cursor over the text that counts lines.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : t_(text) {}
  bool done() const { return i_ >= t_.size(); }
  char peek(size_t ahead = 0) const {
    return i_ + ahead < t_.size() ? t_[i_ + ahead] : '\0';
  }
  bool starts(std::string_view s) const { return t_.substr(i_, s.size()) == s; }
  void next() {
    if (t_[i_] == '\n') ++line_;
    ++i_;
  }
  void skip(size_t n) {
    for (size_t k = 0; k < n && !done(); ++k) next();
  }
  // Moves past `end`, or to the end of the text.
  void past(std::string_view end) {
    while (!done() && !starts(end)) next();
    skip(end.size());
  }
  int line() const { return line_; }

 private:
  std::string_view t_;
  size_t i_ = 0;
  int line_ = 1;
};

}  // namespace

std::optional<std::string> ReadFileAtMost(const std::string& path,
                                          size_t max_bytes) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(
      std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) return std::nullopt;
  std::string bytes;
  // A regular file says its size: refused without reading it.
  struct stat st {};
  if (::fstat(::fileno(f.get()), &st) == 0 && S_ISREG(st.st_mode) &&
      static_cast<unsigned long long>(st.st_size) > max_bytes) {
    throw InputLimitError(path, 0,
                          "larger than " + Bytes(max_bytes) +
                              ", the most mrsim reads from one file");
  }
  char buffer[1 << 16];
  while (true) {
    const size_t n = std::fread(buffer, 1, sizeof(buffer), f.get());
    if (n == 0) break;
    if (bytes.size() + n > max_bytes) {
      throw InputLimitError(path, 0,
                            "larger than " + Bytes(max_bytes) +
                                ", the most mrsim reads from one file");
    }
    bytes.append(buffer, n);
  }
  return bytes;
}

void CheckXmlLimits(std::string_view xml, const std::string& file) {
  if (xml.size() > kMaxInputFileBytes) {
    throw InputLimitError(file, 0,
                          "larger than " + Bytes(kMaxInputFileBytes) +
                              ", the most mrsim reads from one file");
  }
  Scanner s(xml);
  int depth = 0;
  while (!s.done()) {
    if (s.peek() != '<') {
      s.next();
      continue;
    }
    if (s.starts("<!--")) {
      s.past("-->");
    } else if (s.starts("<![CDATA[")) {
      s.past("]]>");
    } else if (s.starts("<?")) {
      s.past("?>");
    } else if (s.starts("<!")) {
      s.past(">");
    } else if (s.starts("</")) {
      s.past(">");
      if (depth > 0) --depth;
    } else {
      // A start tag: its attribute values are quoted and may hold '>'.
      const int line = s.line();
      s.next();
      bool closed = false;
      while (!s.done()) {
        const char c = s.peek();
        if (c == '"' || c == '\'') {
          const int value_line = s.line();
          s.next();
          size_t length = 0;
          while (!s.done() && s.peek() != c) {
            s.next();
            if (++length > kMaxXmlAttributeBytes) {
              throw InputLimitError(
                  file, value_line,
                  "an attribute value longer than " +
                      Bytes(kMaxXmlAttributeBytes) +
                      ", the most an mrsim file's attribute may hold");
            }
          }
          s.next();
        } else if (c == '>') {
          s.next();
          break;
        } else if (c == '/' && s.peek(1) == '>') {
          s.skip(2);
          closed = true;
          break;
        } else {
          s.next();
        }
      }
      if (!closed && ++depth > kMaxXmlDepth) {
        throw InputLimitError(file, line,
                              "elements nested more than " +
                                  std::to_string(kMaxXmlDepth) +
                                  " deep, more than any mrsim file has");
      }
    }
  }
}

}  // namespace mrsim

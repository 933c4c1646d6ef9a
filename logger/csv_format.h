// Number and text formatting for CSV cells. Doubles are written in the
// shortest form that reads back to the same bits (std::to_chars), so a CSV
// loses nothing and live and replayed runs give the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "common/shortest_double.h"

namespace mrsim {

void AppendDouble(double v, std::string* out);
void AppendFloat(float v, std::string* out);
void AppendInt(int64_t v, std::string* out);
// Quotes the text (RFC 4180) when it holds a comma, quote or line break.
void AppendCsvText(std::string_view text, std::string* out);
// Seconds from microseconds, as the `time` column.
inline double SecondsFromUtime(int64_t utime) {
  return static_cast<double>(utime) / 1e6;
}

// Appends cells to a string through a local buffer: one string append per
// few kilobytes instead of one per number (the appends cost about as much
// as the formatting). The text is complete after Flush() or destruction.
class CsvCells {
 public:
  explicit CsvCells(std::string* out) : out_(out) {}
  ~CsvCells() { Flush(); }
  CsvCells(const CsvCells&) = delete;
  CsvCells& operator=(const CsvCells&) = delete;

  // ",<v>"
  void CommaDouble(double v) {
    Make(kMaxDoubleChars + 1);
    *p_++ = ',';
    p_ = WriteDouble(v, p_);
  }
  void Double(double v) {
    Make(kMaxDoubleChars);
    p_ = WriteDouble(v, p_);
  }
  void Flush() {
    out_->append(buf_, p_);
    p_ = buf_;
  }

 private:
  void Make(int n) {
    if (p_ + n > buf_ + sizeof(buf_)) Flush();
  }
  std::string* out_;
  char buf_[4096];
  char* p_ = buf_;
};

}  // namespace mrsim

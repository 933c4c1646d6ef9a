// Number and text formatting for CSV cells. Doubles are written in the
// shortest form that reads back to the same bits (std::to_chars), so a CSV
// loses nothing and live and replayed runs give the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

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

}  // namespace mrsim

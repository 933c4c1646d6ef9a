// Appends CSV lines to one file so that the file always ends with a whole
// line: lines are buffered and written whole, and a failed write (full
// disk) is cut back to the last whole line before the error is reported.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace mrsim {

class CsvWriter {
 public:
  // Creates (truncates) the file. Throws std::runtime_error naming the path.
  explicit CsvWriter(std::string path);
  ~CsvWriter();  // flushes; errors are lost here, call Flush() to see them
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  // Adds one line (without its line break). Writes to the file when the
  // buffer is large; throws like Flush().
  void WriteLine(std::string_view line);
  // Writes every buffered line. Throws std::runtime_error naming the path
  // and the system error; the file then holds every line written before.
  void Flush();

  const std::string& path() const { return path_; }
  int64_t lines() const { return lines_; }
  bool failed() const { return failed_; }
  size_t buffered_bytes() const { return buffer_.size(); }

 private:
  std::string path_;
  int fd_ = -1;
  std::string buffer_;
  int64_t lines_ = 0;
  int64_t committed_ = 0;  // bytes on disk, all whole lines
  bool failed_ = false;
};

}  // namespace mrsim

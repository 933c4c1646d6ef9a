#include "logger/csv_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace mrsim {
namespace {

constexpr size_t kFlushBytes = 1 << 20;

}  // namespace

CsvWriter::CsvWriter(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot create " + path_ + ": " +
                             std::strerror(errno));
  }
  buffer_.reserve(kFlushBytes + (64 << 10));
}

CsvWriter::~CsvWriter() {
  try {
    Flush();
  } catch (const std::exception&) {
    // Reported by an earlier Flush(); a destructor must not throw.
  }
  if (fd_ >= 0) ::close(fd_);
}

void CsvWriter::WriteLine(std::string_view line) {
  if (failed_)
    throw std::runtime_error("earlier write to " + path_ + " failed");
  buffer_.append(line);
  buffer_.push_back('\n');
  ++lines_;
  if (buffer_.size() >= kFlushBytes) Flush();
}

void CsvWriter::Flush() {
  if (failed_)
    throw std::runtime_error("earlier write to " + path_ + " failed");
  size_t done = 0;
  while (done < buffer_.size()) {
    const ssize_t n =
        ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      failed_ = true;
      // Keep only whole lines: drop the part of a line that made it out.
      const size_t last_newline =
          done == 0 ? std::string::npos : buffer_.rfind('\n', done - 1);
      if (last_newline != std::string::npos) {
        committed_ += static_cast<int64_t>(last_newline + 1);
      }
      if (::ftruncate(fd_, committed_) != 0) {
        // Nothing more to do; the error below already names the file.
      }
      buffer_.clear();
      throw std::runtime_error("cannot write " + path_ + ": " +
                               std::strerror(err) +
                               " (kept the lines written before)");
    }
    done += static_cast<size_t>(n);
  }
  committed_ += static_cast<int64_t>(buffer_.size());
  buffer_.clear();
}

}  // namespace mrsim

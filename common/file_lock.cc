#include "common/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace mrsim {
namespace {

// The pid written in the file; 0 when empty or not a number. At most a
// few bytes are read: the file is anyone's to write.
long ReadPid(int fd) {
  char text[32] = {};
  const ssize_t n = pread(fd, text, sizeof(text) - 1, 0);
  if (n <= 0) return 0;
  char* end = nullptr;
  const long pid = std::strtol(text, &end, 10);
  return end != text && pid > 0 ? pid : 0;
}

}  // namespace

FileLock::FileLock(std::string path) : path_(std::move(path)) {
  fd_ = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot open lock file '" + path_ +
                             "': " + std::strerror(errno));
  }
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const long holder = ReadPid(fd_);
    close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK) {
      throw FileLockBusy(
          "'" + path_ + "' is locked by process " +
              (holder > 0 ? std::to_string(holder) : std::string("(unknown)")),
          holder);
    }
    throw std::runtime_error("cannot lock '" + path_ +
                             "': " + std::strerror(error));
  }
  stale_holder_ = ReadPid(fd_);
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd_, 0) != 0 || pwrite(fd_, pid.data(), pid.size(), 0) !=
                                    static_cast<ssize_t>(pid.size())) {
    const int error = errno;
    close(fd_);
    fd_ = -1;
    throw std::runtime_error("cannot write lock file '" + path_ +
                             "': " + std::strerror(error));
  }
}

FileLock::~FileLock() {
  if (fd_ < 0) return;
  // Empty: the next run finds a free lock, not a stale one.
  if (ftruncate(fd_, 0) != 0) {
    // Nothing to do: the lock is released with the descriptor anyway.
  }
  close(fd_);
}

}  // namespace mrsim

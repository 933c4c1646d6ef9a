#include "common/wake_fd.h"

#include <sys/eventfd.h>
#include <unistd.h>

#include <cstdint>
#include <stdexcept>

namespace mrsim {

WakeFd::WakeFd() : fd_(eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  if (fd_ < 0) throw std::runtime_error("eventfd failed");
}

WakeFd::~WakeFd() { close(fd_); }

void WakeFd::Signal() const {
  const std::uint64_t one = 1;
  if (write(fd_, &one, sizeof(one)) < 0) {
    // EAGAIN: the counter is already non-zero, a poll wakes anyway.
  }
}

bool WakeFd::Drain() const {
  std::uint64_t count = 0;
  return read(fd_, &count, sizeof(count)) == sizeof(count) && count > 0;
}

}  // namespace mrsim

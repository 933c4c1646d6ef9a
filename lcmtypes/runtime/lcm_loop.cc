#include "lcmtypes/runtime/lcm_loop.h"

#include <poll.h>

#include <cerrno>
#include <stdexcept>

namespace mrsim {
namespace {

bool Readable(int fd, int timeout_ms) {
  pollfd pfd{fd, POLLIN, 0};
  const int n = poll(&pfd, 1, timeout_ms);
  if (n < 0 && errno != EINTR) throw std::runtime_error("poll on LCM failed");
  return n > 0 && (pfd.revents & POLLIN);
}

template <class Lcm>
int HandleAll(Lcm& lcm, int timeout_ms) {
  const int fd = lcm.getFileno();
  int handled = 0;
  int wait_ms = timeout_ms;
  // Drain what is queued so one slow consumer does not fall behind.
  while (Readable(fd, wait_ms)) {
    errno = 0;
    if (lcm.handle() != 0) {
      // A signal in the middle of a tcpq read (Ctrl-C) is not a broken
      // link: the caller's loop sees the stop flag next.
      if (errno == EINTR) break;
      throw std::runtime_error("lcm handle() failed");
    }
    ++handled;
    wait_ms = 0;
  }
  return handled;
}

}  // namespace

int HandleFor(lcm::LCM& lcm, int timeout_ms) {
  return HandleAll(lcm, timeout_ms);
}
int HandleFor(SignedLcm& lcm, int timeout_ms) {
  return HandleAll(lcm, timeout_ms);
}

}  // namespace mrsim

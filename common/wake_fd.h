// A descriptor another thread makes readable to end a poll() early (an
// eventfd): how a thread that sleeps on a socket learns there is other work.
#pragma once

namespace mrsim {

class WakeFd {
 public:
  // Throws std::runtime_error when the kernel gives no eventfd.
  WakeFd();
  ~WakeFd();
  WakeFd(const WakeFd&) = delete;
  WakeFd& operator=(const WakeFd&) = delete;

  // For poll(): readable once Signal() was called, until Drain().
  int fd() const { return fd_; }
  // Callable from any thread; cheap when already signalled.
  void Signal() const;
  // Makes fd() unreadable again; returns whether it was signalled.
  bool Drain() const;

 private:
  int fd_ = -1;
};

}  // namespace mrsim

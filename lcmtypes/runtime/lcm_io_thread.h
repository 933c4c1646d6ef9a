// Runs the receiving and sending of one lcm::LCM on a thread of its own, so
// a process whose main thread computes (the simulator's physics) pays for
// neither a send, a receive nor a socket wake-up on that thread. On this
// project's 2-core VMs a multicast send costs ~20 us of the sender's time
// (the kernel delivers to every local member and wakes it): a fifth of a
// control period of physics.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <variant>
#include <vector>

#include "common/wake_fd.h"
#include "lcmtypes/runtime/outbox.h"

namespace mrsim {

class LcmIoThread {
 public:
  // Starts handling `lcm` on a new thread: subscription handlers run there
  // from now on. Nothing else may use `lcm` until Stop() returns.
  explicit LcmIoThread(lcm::LCM& lcm);
  // Stop(), with any error of the thread swallowed.
  ~LcmIoThread();
  LcmIoThread(const LcmIoThread&) = delete;
  LcmIoThread& operator=(const LcmIoThread&) = delete;

  // Encodes every message of `out` (on the caller's thread, into recycled
  // buffers), queues them in order for the I/O thread and empties `out`.
  template <class... Messages>
  void PublishAll(Outbox<Messages...>* out);

  // Sends everything queued, then ends the thread. Throws
  // std::runtime_error if LCM failed on the thread (the handle loop's error).
  void Stop();

  // Messages sent so far by the thread (for tests).
  int64_t published() const;

 private:
  struct Encoded {
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  void Queue(std::vector<Encoded>* batch);
  std::vector<uint8_t> TakeBuffer();
  void Loop();

  lcm::LCM& lcm_;
  WakeFd wake_;
  mutable std::mutex mutex_;
  std::vector<Encoded> queue_;               // guarded by mutex_
  std::vector<std::vector<uint8_t>> spare_;  // guarded by mutex_
  int64_t published_ = 0;                    // guarded by mutex_
  bool stop_ = false;                        // guarded by mutex_
  std::exception_ptr error_;                 // set by the thread before it ends
  std::vector<Encoded> batch_;               // caller's scratch
  std::thread thread_;
};

template <class... Messages>
void LcmIoThread::PublishAll(Outbox<Messages...>* out) {
  if (out->empty()) return;
  batch_.clear();
  for (const auto& [channel, message] : out->messages) {
    std::visit(
        [&](const auto& msg) {
          Encoded e{channel, TakeBuffer()};
          const int size = msg.getEncodedSize();
          e.bytes.resize(static_cast<size_t>(size));
          msg.encode(e.bytes.data(), 0, size);
          batch_.push_back(std::move(e));
        },
        message);
  }
  out->clear();
  Queue(&batch_);
}

}  // namespace mrsim

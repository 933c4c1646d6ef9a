// Publishes on a thread of its own, in the order given. On udpm the
// kernel delivers a datagram to every subscriber on the host inside the
// sender's sendmsg, waking each of their threads: the sender's thread pays
// for all of them. A simulator that must not stop stepping hands its
// messages here instead.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace mrsim {

class PublishThread {
 public:
  using Send = std::function<void(const std::string& channel, const void* data,
                                  unsigned size)>;
  // Calls `send` on the thread for each message (tests pass their own).
  explicit PublishThread(Send send);
  // Sends with lcm.publish: `lcm` must outlive this object and take
  // publishes from another thread while its owner handles. LCM's udpm and
  // mpudpm do; tcpq does until its hub goes away (both threads then close
  // the socket).
  explicit PublishThread(lcm::LCM& lcm);
  ~PublishThread();  // sends what is queued, then joins
  PublishThread(const PublishThread&) = delete;
  PublishThread& operator=(const PublishThread&) = delete;

  // Copies the message and returns; the same signature as lcm::LCM's, so
  // PublishAll sends through either.
  int publish(const std::string& channel, const void* data, unsigned size);
  // Returns once every message given so far has been sent.
  void Drain();

 private:
  struct Message {
    std::string channel;
    std::vector<uint8_t> data;
  };
  void Run();

  Send send_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable drained_;
  std::deque<Message> queue_;
  std::vector<Message> spare_;  // sent messages, their buffers reused
  bool sending_ = false;
  bool stop_ = false;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace mrsim

// Publishes on a thread of its own, in the order given. On udpm the
// kernel delivers a datagram to every subscriber on the host inside the
// sender's sendmsg, waking each of their threads: the sender's thread pays
// for all of them. A simulator that must not stop stepping hands its
// messages here instead.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "lcmtypes/runtime/signed_lcm.h"

namespace mrsim {

class PublishThread {
 public:
  using Send = std::function<void(const std::string& channel, const void* data,
                                  unsigned size)>;
  // How the sending thread waits for the next message.
  enum class Wait {
    // Asleep: publish wakes it, a system call on the publishing thread and,
    // when the sender's CPU is idle, an interrupt to that CPU (on a virtual
    // machine several microseconds of the publisher's time).
    kSleep,
    // Spinning at idle priority (SCHED_IDLE) while messages keep coming
    // (gaps under kSpinWindow): publish makes no system call, and the spin
    // takes only CPU time no other thread wants. A thread at normal
    // priority sends what waits longer than kRescue; when the machine has
    // no idle CPU (kRescuesToFallBack such rescues within kRescueWindow, or
    // kLateInARow messages that waited over kLate), it takes over the
    // sending, as kSleep, for good. Until then, on a loaded machine, the
    // idle-priority thread can be pre-empted while it holds the queue's
    // lock or sends: the others then wait until it runs again (wall time
    // only; an unprivileged thread cannot leave idle priority to avoid it).
    kSpin,
  };
  static constexpr std::chrono::microseconds kSpinWindow{1000};
  static constexpr std::chrono::microseconds kRescue{1000};
  static constexpr std::chrono::milliseconds kRescueWindow{1000};
  static constexpr int kRescuesToFallBack = 3;
  static constexpr std::chrono::microseconds kLate{200};
  static constexpr int kLateInARow = 16;

  // Calls `send` on the thread for each message (tests pass their own).
  explicit PublishThread(Send send, Wait wait = Wait::kSleep);
  // Sends with lcm.publish: `lcm` must outlive this object and take
  // publishes from another thread while its owner handles. LCM's udpm and
  // mpudpm do; tcpq does until its hub goes away (both threads then close
  // the socket).
  explicit PublishThread(lcm::LCM& lcm, Wait wait = Wait::kSleep);
  // The same through a SignedLcm: messages are signed on this thread.
  explicit PublishThread(SignedLcm& lcm, Wait wait = Wait::kSleep);
  ~PublishThread();  // sends what is queued, then joins
  PublishThread(const PublishThread&) = delete;
  PublishThread& operator=(const PublishThread&) = delete;

  // Copies the message and returns; the same signature as lcm::LCM's, so
  // PublishAll sends through either.
  int publish(const std::string& channel, const void* data, unsigned size);
  // Returns once every message given so far has been sent.
  void Drain();
  // Whether the idle-priority thread sends (kSpin, and it has not been
  // starved so far).
  bool spinning() const { return spinning_.load(); }
  // Whether all is sent and the sending threads sleep until publish wakes
  // them (when spinning: once kSpinWindow passed without a message).
  bool asleep() const;

 private:
  using Clock = std::chrono::steady_clock;
  struct Message {
    std::string channel;
    std::vector<uint8_t> data;
    Clock::time_point given;
  };
  // Pops the oldest message, sends it unlocked, and keeps its buffers.
  void SendOne(std::unique_lock<std::mutex>& lock);
  void RunSleeping();  // the normal-priority thread; kSpin: also the guard
  void Rescue(std::unique_lock<std::mutex>& lock);
  // How long the oldest message has waited since it could have been sent.
  Clock::duration HeadWaited(Clock::time_point now) const;
  void RunSpinning();  // kSpin: the idle-priority thread
  bool SpinFor(uint64_t seen);

  Send send_;
  mutable std::mutex mutex_;
  std::condition_variable wake_sleeper_;
  std::condition_variable wake_spinner_;
  std::condition_variable drained_;
  std::deque<Message> queue_;
  std::vector<Message> spare_;  // sent messages, their buffers reused
  bool sending_ = false;        // a message is out of the queue, not yet sent
  bool stop_ = false;
  Clock::time_point last_sent_{};          // when the last send ended
  std::deque<Clock::time_point> rescues_;  // kSpin: within kRescueWindow
  bool sleeper_waits_ = false;             // indefinitely: publish must wake it
  bool spinner_waits_ = false;
  // Read by the spinning thread without the lock.
  std::atomic<bool> spinning_;      // the idle-priority thread sends
  std::atomic<uint64_t> given_{0};  // messages published so far
  std::thread sleeper_;  // last: they start once the members above exist
  std::thread spinner_;
};

}  // namespace mrsim

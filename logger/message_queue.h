// Hands received messages from the LCM thread to the writer thread, so the
// LCM handler only copies bytes and never waits on formatting or the disk.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace mrsim {

struct QueuedMessage {
  std::string channel;
  std::vector<uint8_t> data;
  int64_t recv_utime = 0;  // when LCM received it (us since the epoch)
};

class MessageQueue {
 public:
  // Holds at most max_bytes of message data; more is dropped and counted.
  // A waiting PopAll is woken once wake_bytes are queued (or at its
  // timeout): at 1 kHz, waking the writer per message cost the logger more
  // in futex calls and context switches than formatting the CSV.
  explicit MessageQueue(size_t max_bytes, size_t wake_bytes = 1)
      : max_bytes_(max_bytes), wake_bytes_(wake_bytes) {}

  // Copies the message in. False (and counted in dropped()) when full.
  bool Push(const std::string& channel, const void* data, size_t size,
            int64_t recv_utime = 0);
  // Waits up to `timeout` for wake_bytes of messages, then moves every
  // queued one to `out` (appending). False once Close() was called and
  // nothing is left.
  bool PopAll(std::vector<QueuedMessage>* out,
              std::chrono::milliseconds timeout);
  // No more pushes; PopAll returns what is left, then false.
  void Close();

  int64_t dropped() const;
  size_t peak_bytes() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<QueuedMessage> queue_;
  size_t max_bytes_;
  size_t wake_bytes_;
  size_t bytes_ = 0;
  size_t peak_bytes_ = 0;
  int64_t dropped_ = 0;
  bool closed_ = false;
};

}  // namespace mrsim

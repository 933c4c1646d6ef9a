#include "logger/message_queue.h"

#include <algorithm>

namespace mrsim {

bool MessageQueue::Push(const std::string& channel, const void* data,
                        size_t size, int64_t recv_utime) {
  QueuedMessage m;
  m.channel = channel;
  m.recv_utime = recv_utime;
  const uint8_t* bytes = static_cast<const uint8_t*>(data);
  m.data.assign(bytes, bytes + size);
  bool wake = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_ || bytes_ + size > max_bytes_) {
      ++dropped_;
      return false;
    }
    wake = bytes_ < wake_bytes_ && bytes_ + size >= wake_bytes_;
    bytes_ += size;
    peak_bytes_ = std::max(peak_bytes_, bytes_);
    queue_.push_back(std::move(m));
  }
  if (wake) ready_.notify_one();
  return true;
}

bool MessageQueue::PopAll(std::vector<QueuedMessage>* out,
                          std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  ready_.wait_for(lock, timeout,
                  [this] { return bytes_ >= wake_bytes_ || closed_; });
  if (queue_.empty()) return !closed_;
  for (QueuedMessage& m : queue_) out->push_back(std::move(m));
  queue_.clear();
  bytes_ = 0;
  return true;
}

void MessageQueue::Close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
}

int64_t MessageQueue::dropped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return dropped_;
}

size_t MessageQueue::peak_bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return peak_bytes_;
}

}  // namespace mrsim

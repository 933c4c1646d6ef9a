#include "lcmtypes/runtime/publish_thread.h"

namespace mrsim {

PublishThread::PublishThread(Send send)
    : send_(std::move(send)), thread_([this] { Run(); }) {}

PublishThread::PublishThread(lcm::LCM& lcm)
    : PublishThread(
          [&lcm](const std::string& channel, const void* data, unsigned size) {
            // A failed send is LCM's to report (it prints); the simulator
            // could do no more.
            lcm.publish(channel, data, size);
          }) {}

PublishThread::~PublishThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

int PublishThread::publish(const std::string& channel, const void* data,
                           unsigned size) {
  const uint8_t* bytes = static_cast<const uint8_t*>(data);
  bool idle = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Message m;
    if (!spare_.empty()) {
      m = std::move(spare_.back());
      spare_.pop_back();
    }
    m.channel = channel;
    m.data.assign(bytes, bytes + size);
    idle = queue_.empty() && !sending_;
    queue_.push_back(std::move(m));
  }
  // Only a waiting thread needs the wake-up (a system call).
  if (idle) wake_.notify_one();
  return 0;
}

void PublishThread::Drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  drained_.wait(lock, [this] { return queue_.empty() && !sending_; });
}

void PublishThread::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, nothing left
    Message m = std::move(queue_.front());
    queue_.pop_front();
    sending_ = true;
    lock.unlock();
    send_(m.channel, m.data.data(), static_cast<unsigned>(m.data.size()));
    lock.lock();
    sending_ = false;
    if (spare_.size() < 8) spare_.push_back(std::move(m));
    if (queue_.empty()) drained_.notify_all();
  }
}

}  // namespace mrsim

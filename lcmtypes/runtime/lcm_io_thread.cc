#include "lcmtypes/runtime/lcm_io_thread.h"

#include <poll.h>

#include <cerrno>
#include <stdexcept>

namespace mrsim {
namespace {

// The longest the thread sleeps without looking at its stop flag; Stop()
// wakes it at once, so this only bounds a lost wake-up.
constexpr int kPollMs = 100;
// Spare encode buffers kept for reuse.
constexpr size_t kMaxSpare = 64;

}  // namespace

LcmIoThread::LcmIoThread(lcm::LCM& lcm) : lcm_(lcm) {
  thread_ = std::thread([this] { Loop(); });
}

LcmIoThread::~LcmIoThread() {
  try {
    Stop();
  } catch (...) {
    // A destructor has nobody to report to; Stop() was the place.
  }
}

void LcmIoThread::Stop() {
  if (thread_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.Signal();
    thread_.join();
    if (error_) std::rethrow_exception(error_);
  }
}

int64_t LcmIoThread::published() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return published_;
}

std::vector<uint8_t> LcmIoThread::TakeBuffer() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (spare_.empty()) return {};
  std::vector<uint8_t> b = std::move(spare_.back());
  spare_.pop_back();
  return b;
}

void LcmIoThread::Queue(std::vector<Encoded>* batch) {
  bool was_empty = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    was_empty = queue_.empty();
    for (Encoded& e : *batch) queue_.push_back(std::move(e));
  }
  batch->clear();
  // A non-empty queue means the thread has been woken already.
  if (was_empty) wake_.Signal();
}

void LcmIoThread::Loop() {
  std::vector<Encoded> sending;
  try {
    for (;;) {
      pollfd fds[2] = {{lcm_.getFileno(), POLLIN, 0}, {wake_.fd(), POLLIN, 0}};
      const int ready = poll(fds, 2, kPollMs);
      if (ready < 0 && errno != EINTR) {
        throw std::runtime_error("poll on LCM failed");
      }
      if (ready > 0 && (fds[0].revents & POLLIN)) {
        if (lcm_.handle() != 0) throw std::runtime_error("lcm handle() failed");
      }
      if (ready > 0 && (fds[1].revents & POLLIN)) wake_.Drain();
      bool stop = false;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        sending.swap(queue_);
        stop = stop_;
      }
      for (const Encoded& e : sending) {
        lcm_.publish(e.channel, e.bytes.data(),
                     static_cast<unsigned>(e.bytes.size()));
      }
      if (!sending.empty()) {
        std::lock_guard<std::mutex> lock(mutex_);
        published_ += static_cast<int64_t>(sending.size());
        for (Encoded& e : sending) {
          if (spare_.size() < kMaxSpare) spare_.push_back(std::move(e.bytes));
        }
      }
      sending.clear();
      if (stop) return;  // the queue was swapped out and sent after stop_
    }
  } catch (...) {
    error_ = std::current_exception();
  }
}

}  // namespace mrsim

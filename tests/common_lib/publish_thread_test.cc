#include "lcmtypes/runtime/publish_thread.h"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

namespace mrsim {
namespace {

// Records what the thread sends; the first send can be held at a gate so
// that the messages behind it queue up.
class Recorder {
 public:
  void Send(const std::string& channel, const void* data, unsigned size) {
    std::unique_lock<std::mutex> lock(mutex_);
    gate_.wait(lock, [this] { return open_; });
    const char* text = static_cast<const char*>(data);
    sent_.push_back(channel + ":" + std::string(text, size));
  }
  void Hold() {
    std::lock_guard<std::mutex> lock(mutex_);
    open_ = false;
  }
  void Open() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      open_ = true;
    }
    gate_.notify_all();
  }
  std::vector<std::string> sent() {
    std::lock_guard<std::mutex> lock(mutex_);
    return sent_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable gate_;
  bool open_ = true;
  std::vector<std::string> sent_;
};

PublishThread::Send To(Recorder& r) {
  return [&r](const std::string& c, const void* d, unsigned n) {
    r.Send(c, d, n);
  };
}

TEST(PublishThread, SendsCopiesInOrderAndDrainWaitsForAll) {
  Recorder recorder;
  PublishThread thread(To(recorder));
  recorder.Hold();
  std::vector<std::string> expected;
  std::string buffer;
  for (int i = 0; i < 50; ++i) {
    buffer = "state " + std::to_string(i);
    const std::string channel = i % 2 ? "A" : "B";
    thread.publish(channel, buffer.data(),
                   static_cast<unsigned>(buffer.size()));
    buffer.assign(buffer.size(), 'x');  // the caller reuses its buffer
    expected.push_back(channel + ":state " + std::to_string(i));
  }
  recorder.Open();
  thread.Drain();
  EXPECT_EQ(recorder.sent(), expected);
}

TEST(PublishThread, DestructionSendsWhatIsStillQueued) {
  Recorder recorder;
  {
    PublishThread thread(To(recorder));
    recorder.Hold();
    for (int i = 0; i < 10; ++i) {
      const std::string text = std::to_string(i);
      thread.publish("S", text.data(), static_cast<unsigned>(text.size()));
    }
    recorder.Open();
  }
  ASSERT_EQ(recorder.sent().size(), 10u);
  EXPECT_EQ(recorder.sent().back(), "S:9");
}

}  // namespace
}  // namespace mrsim

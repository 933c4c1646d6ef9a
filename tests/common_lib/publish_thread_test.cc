#include "lcmtypes/runtime/publish_thread.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

namespace mrsim {

// Names the parameter in test output.
void PrintTo(PublishThread::Wait wait, std::ostream* os) {
  *os << (wait == PublishThread::Wait::kSpin ? "kSpin" : "kSleep");
}

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

// Every behaviour holds whether the sender sleeps or spins.
class PublishThreadWait : public ::testing::TestWithParam<PublishThread::Wait> {
};

TEST_P(PublishThreadWait, SendsCopiesInOrderAndDrainWaitsForAll) {
  Recorder recorder;
  PublishThread thread(To(recorder), GetParam());
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

TEST_P(PublishThreadWait, DestructionSendsWhatIsStillQueued) {
  Recorder recorder;
  {
    PublishThread thread(To(recorder), GetParam());
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

// Should `done` not come true within 10 s, returns false.
bool WaitUntil(const std::function<bool()>& done) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::yield();
  }
  return true;
}

// A stream in bursts, with quiet spells in which the sending threads fall
// asleep and publish must wake them; on a loaded machine (ctest -j) the
// normal-priority thread sends what waits and may take over. Nothing is
// lost, doubled or reordered on the way.
TEST_P(PublishThreadWait, StreamWithQuietSpellsArrivesWholeAndInOrder) {
  Recorder recorder;
  std::vector<std::string> expected;
  {
    PublishThread thread(To(recorder), GetParam());
    for (int i = 0; i < 3000; ++i) {
      const std::string text = std::to_string(i);
      thread.publish("S", text.data(), static_cast<unsigned>(text.size()));
      expected.push_back("S:" + text);
      if (i % 500 == 499) {
        ASSERT_TRUE(WaitUntil([&] { return thread.asleep(); })) << i;
      } else if (i % 7 == 0) {
        thread.Drain();  // the spinner watches an empty queue
      }
    }
    thread.Drain();
    EXPECT_EQ(recorder.sent(), expected);
  }
  EXPECT_EQ(recorder.sent().size(), expected.size());
}

TEST(PublishThread, OnlyTheSpinningModeSpins) {
  Recorder recorder;
  PublishThread sleeping(To(recorder), PublishThread::Wait::kSleep);
  EXPECT_FALSE(sleeping.spinning());
}

INSTANTIATE_TEST_SUITE_P(
    BothWaits, PublishThreadWait,
    ::testing::Values(PublishThread::Wait::kSleep, PublishThread::Wait::kSpin),
    [](const ::testing::TestParamInfo<PublishThread::Wait>& info) {
      return info.param == PublishThread::Wait::kSpin ? std::string("Spin")
                                                      : std::string("Sleep");
    });

}  // namespace
}  // namespace mrsim

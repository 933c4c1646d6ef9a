// LcmIoThread on in-process LCM (memq://): what the simulator relies on when
// its sending and receiving leave the physics thread.
#include "lcmtypes/runtime/lcm_io_thread.h"

#include <gtest/gtest.h>

#include <atomic>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "mrsim/sim_status_t.hpp"
#include "tests/common/wait_until.h"

namespace mrsim {
namespace {

using Box = Outbox<sim_status_t>;

sim_status_t Status(int64_t seq) {
  sim_status_t s{};
  s.seq = seq;
  s.clock = "lockstep";
  return s;
}

struct Heard {
  std::mutex mutex;
  std::vector<int64_t> seqs;
  std::thread::id thread;
  void On(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    sim_status_t s;
    if (s.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) {
      return;
    }
    std::lock_guard<std::mutex> lock(mutex);
    seqs.push_back(s.seq);
    thread = std::this_thread::get_id();
  }
  size_t size() {
    std::lock_guard<std::mutex> lock(mutex);
    return seqs.size();
  }
};

TEST(LcmIoThread, SendsInOrderAndRunsHandlersOnItsOwnThread) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Heard heard;
  lcm.subscribe("STATUS", &Heard::On, &heard);
  LcmIoThread io(lcm);
  Box box;
  for (int64_t i = 0; i < 500; ++i) {
    box.Add("STATUS", Status(i));
    if (i % 7 == 0) io.PublishAll(&box);  // batches of several sizes
  }
  io.PublishAll(&box);
  EXPECT_TRUE(box.empty());
  ASSERT_TRUE(testing::WaitUntil([&] { return heard.size() == 500; }, 30.0))
      << heard.size();
  io.Stop();
  EXPECT_EQ(io.published(), 500);
  for (int64_t i = 0; i < 500; ++i) EXPECT_EQ(heard.seqs[i], i);
  EXPECT_NE(heard.thread, std::this_thread::get_id());
}

TEST(LcmIoThread, StopSendsEverythingQueuedFirst) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Heard heard;
  lcm.subscribe("STATUS", &Heard::On, &heard);
  int64_t published = 0;
  {
    LcmIoThread io(lcm);
    Box box;
    for (int64_t i = 0; i < 100; ++i) box.Add("STATUS", Status(i));
    io.PublishAll(&box);
    io.Stop();  // the final status of a stopping simulator must go out
    published = io.published();
  }
  EXPECT_EQ(published, 100);
  // memq delivers on the next handle(): the stopped thread no longer runs
  // one, this thread may again.
  while (lcm.handleTimeout(0) > 0) {
  }
  EXPECT_EQ(heard.size(), 100u);
}

}  // namespace
}  // namespace mrsim

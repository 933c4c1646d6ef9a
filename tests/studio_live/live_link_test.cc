// Smoke test: the studio's LCM node attached to a real mrsim-sim started in
// another process, over its own multicast port.
#include "studio/live/live_link.h"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>

#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

// Polls until `done` holds or `timeout_s` passes; publishes nothing.
bool PollUntil(LiveLink& link, const std::function<bool()>& done,
               double timeout_s) {
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    link.Poll(50);
  }
  return true;
}

TEST(LiveLink, AttachesToARunningSimulationSteersPausesAndStepsIt) {
  const std::string url = TestLcmUrl(7965);
  const std::string dir = TempDir("live_link");
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"),
                    SourcePath("scenarios/case_study.xml"), "--lcm-url", url,
                    "--clock", "realtime", "--rate", "100"},
                   dir + "/sim.log");
  ChildProcess gait({BinaryPath("gait_controller/process/mrsim-gait"),
                     "--robot", "case_study", "--scenario",
                     SourcePath("scenarios/case_study.xml"), "--lcm-url", url},
                    dir + "/gait.log");
  LiveSessionOptions options;
  options.sender = "studio-test";
  options.request_timeout_s = 10;  // a loaded machine answers late
  LiveSession session(options);
  LiveLink link(url, &session);

  ASSERT_TRUE(PollUntil(
      link, [&] { return session.robot("case_study") != nullptr; }, 60))
      << sim.Output();
  ASSERT_TRUE(PollUntil(
      link, [&] { return session.sim_status().has_value(); }, 30));

  // Steer: mrsim-gait (another process) acknowledges and runs it.
  ASSERT_TRUE(PollUntil(
      link, [&] { return session.robot("case_study")->gait.has_value(); }, 30))
      << gait.Output();
  StudioOutbox out;
  const int64_t turn =
      session.Steer("case_study", "turn-left", 0.5, WallClock::now(), &out);
  link.Publish(&out);
  ASSERT_TRUE(PollUntil(
      link,
      [&] {
        return session.request(turn)->state != LiveRequest::State::kPending;
      },
      30));
  EXPECT_EQ(session.request(turn)->state, LiveRequest::State::kDone)
      << session.request(turn)->error;
  ASSERT_TRUE(PollUntil(
      link,
      [&] { return session.robot("case_study")->gait->motion == "turn-left"; },
      30));

  // Pause: acknowledged, and sim time stops.
  const int64_t pause = session.Pause(WallClock::now(), &out);
  link.Publish(&out);
  ASSERT_TRUE(PollUntil(
      link,
      [&] {
        return session.request(pause)->state != LiveRequest::State::kPending;
      },
      30));
  ASSERT_EQ(session.request(pause)->state, LiveRequest::State::kDone)
      << session.request(pause)->error;
  // The status answering the pause was sent after the pause took effect.
  const double paused_at = session.sim_status()->sim_time;

  // Step 10 periods of 10 ms: 0.1 s more, then paused again.
  const int64_t step = session.Step(10, WallClock::now(), &out);
  link.Publish(&out);
  ASSERT_TRUE(PollUntil(
      link,
      [&] {
        return session.request(step)->state != LiveRequest::State::kPending;
      },
      30));
  ASSERT_EQ(session.request(step)->state, LiveRequest::State::kDone)
      << session.request(step)->error;
  ASSERT_TRUE(PollUntil(
      link,
      [&] {
        return session.robot("case_study")->state.sim_time >=
               paused_at + 0.1 - 1e-9;
      },
      30));
  EXPECT_NEAR(session.robot("case_study")->state.sim_time, paused_at + 0.1,
              1e-9);
  EXPECT_EQ(session.malformed(), 0);
  EXPECT_EQ(session.foreign(), 0);
}

}  // namespace
}  // namespace mrsim::studio

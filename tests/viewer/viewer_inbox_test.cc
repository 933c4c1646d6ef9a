// The viewer's message intake: what it accepts, what it counts and drops,
// and the gait text it takes from gait commands.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/physics.h"
#include "tests/viewer/viewer_test_util.h"
#include "viewer/frame_scheduler.h"
#include "viewer/gl_context.h"
#include "viewer/process/state_inbox.h"
#include "viewer/state_viewer.h"

namespace mrsim {
namespace {

template <typename Msg>
std::vector<unsigned char> Bytes(const Msg& msg) {
  std::vector<unsigned char> bytes(msg.getEncodedSize());
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

TEST(ViewerInbox, DropsAndCountsMalformedStatesAndFollowsGaitCommands) {
  GlContext gl;
  const Scenario scenario = testing::ViewerTestScenario();
  ViewerOptions options;
  options.width = 64;
  options.height = 48;
  StateViewer viewer(scenario, options);
  FrameScheduler scheduler(10.0, viewer.robot_count());
  StateInbox inbox(viewer, "MRSIM", &scheduler);
  const std::string channel = StateChannel("MRSIM", "snake");
  EXPECT_EQ(inbox.gait_channel(), GaitChannel("MRSIM", "snake"));

  Physics physics(scenario);
  physics.Step();
  const RobotState good = physics.ReadRobotState(0);
  auto send = [&](const RobotState& s, int64_t seq) {
    const std::vector<unsigned char> b = Bytes(ToRobotStateMessage(s, seq));
    return inbox.Receive(channel, b.data(), static_cast<int>(b.size()));
  };

  const unsigned char junk[] = {1, 2, 3};
  EXPECT_FALSE(inbox.Receive(channel, junk, sizeof(junk)));
  RobotState short_state = good;
  short_state.frames.pop_back();
  EXPECT_FALSE(send(short_state, 1));
  RobotState nan_state = good;
  nan_state.frames[0].position.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(send(nan_state, 2));
  RobotState other = good;
  other.robot = "someone_else";
  EXPECT_FALSE(send(other, 3));
  EXPECT_EQ(inbox.malformed(), 4);
  EXPECT_EQ(inbox.accepted(), 0);

  EXPECT_TRUE(send(good, 4));
  EXPECT_EQ(inbox.accepted(), 1);
  EXPECT_FALSE(inbox.Receive("MRSIM_STATE_nobody", junk, sizeof(junk)));
  EXPECT_EQ(inbox.malformed(), 4);  // not ours: ignored, not counted

  gait_command_t gait{};
  gait.robot = "snake";
  gait.gait = "forward-strong";
  std::vector<unsigned char> b = Bytes(gait);
  EXPECT_TRUE(inbox.Receive(inbox.gait_channel(), b.data(),
                            static_cast<int>(b.size())));
  EXPECT_EQ(inbox.gait_text(), "forward-strong");
  gait.gait = "";
  gait.motion = "turn-left";
  b = Bytes(gait);
  inbox.Receive(inbox.gait_channel(), b.data(), static_cast<int>(b.size()));
  EXPECT_EQ(inbox.gait_text(), "forward-strong (turn-left)");

  // mrsim-gait's status says what really runs (keyboard steering too) and
  // wins over the commands from then on.
  gait_status_t status{};
  status.robot = "snake";
  status.gait = "sidewind";
  status.motion = "sidewind-left";
  b = Bytes(status);
  EXPECT_TRUE(inbox.Receive(inbox.gait_status_channel(), b.data(),
                            static_cast<int>(b.size())));
  EXPECT_EQ(inbox.gait_text(), "sidewind (sidewind-left)");
  b = Bytes(gait);
  inbox.Receive(inbox.gait_channel(), b.data(), static_cast<int>(b.size()));
  EXPECT_EQ(inbox.gait_text(), "sidewind (sidewind-left)");

  // A live viewer subscribes to exactly what the inbox takes.
  const auto all = inbox.AllChannels();
  for (const std::string& channel :
       {inbox.gait_status_channel(), inbox.gait_channel(),
        inbox.scene_channel(), inbox.channels().begin()->first}) {
    EXPECT_NE(std::find(all.begin(), all.end(), channel), all.end()) << channel;
  }
}

// --exit-with-sim follows the simulator's status: the inbox listens on its
// channel, keeps the newest well-formed status and counts the rest.
TEST(ViewerInbox, KeepsTheSimulatorsStatusAndDropsAMalformedOne) {
  GlContext gl;
  const Scenario scenario = testing::ViewerTestScenario();
  ViewerOptions options;
  options.width = 64;
  options.height = 48;
  StateViewer viewer(scenario, options);
  FrameScheduler scheduler(10.0, viewer.robot_count());
  StateInbox inbox(viewer, "MRSIM", &scheduler);
  const std::vector<std::string> all = inbox.AllChannels();
  EXPECT_NE(std::find(all.begin(), all.end(), SimStatusChannel("MRSIM")),
            all.end());
  EXPECT_FALSE(inbox.last_status().has_value());

  const unsigned char junk[] = {9, 9, 9, 9, 9, 9, 9, 9, 9};
  EXPECT_FALSE(inbox.Receive(inbox.status_channel(), junk, sizeof(junk)));
  EXPECT_EQ(inbox.malformed(), 1);
  EXPECT_EQ(inbox.statuses(), 0);

  sim_status_t status{};
  status.mode = sim_status_t::RUNNING;
  std::vector<unsigned char> b = Bytes(status);
  EXPECT_TRUE(inbox.Receive(inbox.status_channel(), b.data(),
                            static_cast<int>(b.size())));
  status.mode = sim_status_t::STOPPING;
  b = Bytes(status);
  EXPECT_TRUE(inbox.Receive(inbox.status_channel(), b.data(),
                            static_cast<int>(b.size())));
  EXPECT_EQ(inbox.statuses(), 2);
  ASSERT_TRUE(inbox.last_status().has_value());
  // lcm-gen's constants are declared, not defined: compared as values.
  const int stopping = sim_status_t::STOPPING;
  EXPECT_EQ(inbox.last_status()->mode, stopping);
  EXPECT_EQ(inbox.accepted(), 0);  // a status is no robot state
}

}  // namespace
}  // namespace mrsim

// The LCM side of mrsim-gait in process (memq://): answers, repeats, resets,
// rate, queued and bad gait commands; command parsing; joint axes.
#include "gait_controller/process/gait_node.h"

#include <gtest/gtest.h>

#include <cmath>
#include <lcm/lcm-cpp.hpp>

#include "gait_controller/gait_presets.h"
#include "gait_controller/process/gait_command_apply.h"
#include "gait_controller/process/joint_axes_spec.h"
#include "lcmtypes/runtime/channels.h"

namespace mrsim {
namespace {

struct Commands {
  std::vector<joint_command_t> got;
  void On(const lcm::ReceiveBuffer*, const std::string&,
          const joint_command_t* msg) {
    got.push_back(*msg);
  }
};

robot_state_t State(int64_t seq, double t, int joints = 4) {
  robot_state_t s{};
  s.seq = seq;
  s.sim_time = t;
  s.utime = static_cast<int64_t>(std::llround(t * 1e6));
  s.robot = "snake";
  s.num_joints = joints;
  s.joints.resize(joints);
  return s;
}

class GaitNodeTest : public ::testing::Test {
 protected:
  GaitNodeTest() : lcm_("memq://") {
    lcm_.subscribe(CommandChannel("MRSIM", "snake"), &Commands::On, &out_);
  }
  std::unique_ptr<GaitNode> Make(double rate = 100.0) {
    GaitNodeOptions o;
    o.robot = "snake";
    o.sender = "g";
    o.rate = rate;
    return std::make_unique<GaitNode>(
        lcm_, o, [](int n) { return JointAxesSpec("pitch").Expand(n); },
        *FindGaitPreset("forward"));
  }
  void Send(const robot_state_t& s) {
    lcm_.publish(StateChannel("MRSIM", "snake"), &s);
    while (lcm_.handleTimeout(0) > 0) {
    }
  }
  void SendGait(const gait_command_t& c) {
    lcm_.publish(GaitChannel("MRSIM", "snake"), &c);
    while (lcm_.handleTimeout(0) > 0) {
    }
  }
  lcm::LCM lcm_;
  Commands out_;
};

TEST_F(GaitNodeTest, AnswersEachStateOnceWithTheControllersTargets) {
  auto node = Make();
  GaitController reference(std::vector<Axis>(4, Axis::kPitch));
  reference.SetGait(*FindGaitPreset("forward"));
  for (int k = 0; k < 200; ++k) {
    const double t = k * 0.01;
    Send(State(k, t));
    // The clock is the states' sim time: dt is the difference of two.
    const auto& want = reference.Update(k == 0 ? 0.0 : t - (k - 1) * 0.01);
    ASSERT_EQ(out_.got.size(), static_cast<size_t>(k + 1));
    const joint_command_t& c = out_.got.back();
    EXPECT_EQ(c.state_seq, k);
    EXPECT_EQ(c.sender, "g");
    EXPECT_EQ(c.robot, "snake");
    EXPECT_EQ(c.target, want) << k;
  }
  EXPECT_EQ(node->counters().states_answered, 200);
}

TEST_F(GaitNodeTest, RepeatedStateGetsTheSameAnswerOlderIsIgnored) {
  auto node = Make();
  for (int k = 0; k < 150; ++k) Send(State(k, k * 0.01));
  const joint_command_t last = out_.got.back();
  Send(State(149, 1.49));
  ASSERT_EQ(out_.got.size(), 151u);
  EXPECT_EQ(out_.got.back().target, last.target);
  EXPECT_EQ(out_.got.back().seq, last.seq);
  Send(State(100, 1.0));
  EXPECT_EQ(out_.got.size(), 151u);
  EXPECT_EQ(node->counters().states_repeated, 1);
  EXPECT_EQ(node->counters().states_skipped, 1);
}

TEST_F(GaitNodeTest, SimTimeGoingBackRestartsFromRest) {
  auto node = Make();
  for (int k = 0; k < 150; ++k) Send(State(k, k * 0.01));
  EXPECT_NE(out_.got.back().target, std::vector<double>(4, 0.0));
  Send(State(150, 0.0));  // a reset: seq goes on, time starts again
  EXPECT_EQ(out_.got.back().target, std::vector<double>(4, 0.0));
}

TEST_F(GaitNodeTest, RateSkipsStatesThatComeTooOften) {
  auto node = Make(50.0);
  for (int k = 0; k < 100; ++k) Send(State(k, k * 0.01));
  EXPECT_EQ(node->counters().states_answered, 50);
  EXPECT_EQ(node->counters().states_skipped, 50);
}

TEST_F(GaitNodeTest, SkippedStateSentAgainSwitchesToEveryState) {
  auto node = Make(50.0);
  Send(State(0, 0.0));
  Send(State(1, 0.01));  // skipped at 50 Hz
  EXPECT_EQ(out_.got.size(), 1u);
  Send(State(1, 0.01));  // lockstep: the simulator waits for an answer
  ASSERT_EQ(out_.got.size(), 2u);
  EXPECT_EQ(out_.got.back().state_seq, 1);
  Send(State(2, 0.02));
  EXPECT_EQ(out_.got.size(), 3u);
  bool noted = false;
  for (const auto& line : node->TakeLog()) {
    noted = noted || line.find("answering every state") != std::string::npos;
  }
  EXPECT_TRUE(noted);
}

TEST_F(GaitNodeTest, ForeignAndMalformedStatesAreCountedNotAnswered) {
  auto node = Make();
  robot_state_t other = State(0, 0);
  other.robot = "other";
  Send(other);
  robot_state_t nan = State(0, std::nan(""));
  Send(nan);
  const char garbage[] = "garbage";
  lcm_.publish(StateChannel("MRSIM", "snake"), garbage, sizeof(garbage));
  while (lcm_.handleTimeout(0) > 0) {
  }
  Send(State(1, 0.01));
  Send(State(2, 0.02, 5));  // wrong joint count for this robot
  EXPECT_EQ(out_.got.size(), 1u);
  EXPECT_EQ(node->counters().states_foreign, 1);
  EXPECT_EQ(node->counters().messages_malformed, 3);
}

TEST_F(GaitNodeTest, AxesThatDoNotFitStopTheNode) {
  GaitNodeOptions o;
  o.robot = "snake";
  GaitNode node(
      lcm_, o, [](int n) { return JointAxesSpec("PYP").Expand(n); },
      *FindGaitPreset("forward"));
  Send(State(0, 0));
  EXPECT_NE(node.error().find("--axes lists 3 joints but the robot has 4"),
            std::string::npos)
      << node.error();
  EXPECT_TRUE(out_.got.empty());
}

TEST_F(GaitNodeTest, GaitCommandsBeforeTheFirstStateAreQueued) {
  auto node = Make();
  gait_command_t c{};
  c.motion = "backward";
  c.strength = 1;
  SendGait(c);
  EXPECT_EQ(node->controller(), nullptr);
  Send(State(0, 0));
  ASSERT_NE(node->controller(), nullptr);
  EXPECT_EQ(node->controller()->motion(), Motion::kBackward);
  EXPECT_EQ(node->counters().commands_applied, 1);
}

TEST(GaitCommandApply, AppliesEveryPartInOrder) {
  GaitController c(std::vector<Axis>(6, Axis::kPitch));
  gait_command_t cmd{};
  cmd.gait = "forward-strong";
  cmd.has_parameters = true;
  const double p[7] = {0.7, 0, 2, 0, 3, 0.1, 0};
  std::copy(p, p + 7, cmd.parameters);
  cmd.motion = "backward";
  cmd.strength = 0.5;
  const std::string what = ApplyGaitCommand(cmd, &c);
  EXPECT_NE(what.find("gait forward-strong"), std::string::npos) << what;
  EXPECT_EQ(c.active_gait().parameters.ToVector(),
            std::vector<double>(p, p + 7));
  EXPECT_EQ(c.motion(), Motion::kBackward);
  EXPECT_EQ(c.strength(), 0.5);
}

TEST(GaitCommandApply, ABadPartRejectsTheWholeCommand) {
  GaitController c(std::vector<Axis>(6, Axis::kPitch));
  gait_command_t cmd{};
  cmd.gait = "forward-strong";
  cmd.motion = "moonwalk";
  EXPECT_THROW(ApplyGaitCommand(cmd, &c), std::invalid_argument);
  EXPECT_EQ(c.active_gait().name, "forward");
  cmd = {};
  cmd.has_direction = true;
  cmd.forward = 0.5;
  cmd.turn = std::nan("");
  EXPECT_THROW(ApplyGaitCommand(cmd, &c), std::invalid_argument);
  EXPECT_EQ(c.motion(), Motion::kForward);
  cmd = {};
  EXPECT_THROW(ApplyGaitCommand(cmd, &c), std::invalid_argument);
}

TEST(GaitJointAxes, PatternsAndLetters) {
  const auto py = JointAxesSpec("pitch-yaw").Expand(5);
  EXPECT_EQ(py, (std::vector<Axis>{Axis::kPitch, Axis::kYaw, Axis::kPitch,
                                   Axis::kYaw, Axis::kPitch}));
  EXPECT_EQ(JointAxesSpec("yaw-pitch").Expand(2),
            (std::vector<Axis>{Axis::kYaw, Axis::kPitch}));
  EXPECT_EQ(JointAxesSpec("yyp").Expand(3),
            (std::vector<Axis>{Axis::kYaw, Axis::kYaw, Axis::kPitch}));
  EXPECT_THROW(JointAxesSpec("PYX"), std::invalid_argument);
  EXPECT_THROW(JointAxesSpec("PY").Expand(3), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim

// mrsim-nn's node in process with a fake clock: it answers each state with
// the network's targets for that state (the same as the network fed the
// physics' state in process), repeats lost answers, and stops when the
// robot does not fit the network.
#include "nn_controller/process/nn_node.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lcmtypes/runtime/channels.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/physics.h"

namespace mrsim {
namespace {

MlpNetwork Net(int joints) {
  MlpShape s;
  s.joints = joints;
  s.hidden = {5};
  s.imu = true;
  s.sensors = 3;
  std::vector<double> w(static_cast<size_t>(s.WeightCount()));
  for (size_t i = 0; i < w.size(); ++i) w[i] = std::sin(0.9 * i + 0.1);
  return MlpNetwork(s, w, 1.3);
}

robot_state_t State(int64_t seq, double t, int joints = 4) {
  robot_state_t s{};
  s.seq = seq;
  s.sim_time = t;
  s.utime = static_cast<int64_t>(std::llround(t * 1e6));
  s.robot = "snake";
  s.num_joints = joints;
  s.joints.resize(joints);
  for (int j = 0; j < joints; ++j) s.joints[j].angle = 0.1 * j + t;
  s.orientation[0] = 1;
  return s;
}

class NnNodeTest : public ::testing::Test {
 protected:
  NnNode Make(int joints = 4) {
    NnNodeOptions o;
    o.robot = "snake";
    o.sender = "nn-snake";
    o.rate = 0;
    return NnNode(o, Net(joints), now_);
  }
  std::vector<joint_command_t> Send(NnNode& node, const robot_state_t& s) {
    node.OnState(s, now_, &out_);
    std::vector<joint_command_t> got;
    for (auto& [channel, msg] : out_.messages) {
      EXPECT_EQ(channel, CommandChannel("MRSIM", "snake"));
      got.push_back(std::get<joint_command_t>(msg));
    }
    out_.clear();
    return got;
  }
  WallTime now_{};
  NnOutbox out_;
};

TEST_F(NnNodeTest, AnswersEachStateWithTheNetworksTargets) {
  NnNode node = Make();
  MlpNetwork reference = Net(4);
  for (int k = 0; k < 5; ++k) {
    const robot_state_t state = State(k, k * 0.01);
    const auto got = Send(node, state);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].state_seq, k);
    EXPECT_EQ(got[0].sender, "nn-snake");
    NnObservation o;
    ObservationOfMessage(state, &o);
    EXPECT_EQ(got[0].target, reference.Evaluate(o));
  }
  EXPECT_EQ(node.counters().states_answered, 5);
}

TEST_F(NnNodeTest, ReadsTheMessageAsTheRunnerReadsThePhysics) {
  // The optimiser's episode reads RobotState, mrsim-nn its message: the
  // network must see the same numbers, sensors and IMU included.
  ChainOptions options;
  options.modules = 5;
  Scenario scenario;
  scenario.robots.push_back(MakeChain(options));
  Physics physics(scenario);
  physics.Step(20);
  const RobotState state = physics.ReadRobotState(0);
  NnObservation from_physics, from_message;
  ObservationOf(state, &from_physics);
  ObservationOfMessage(ToRobotStateMessage(state, 3), &from_message);
  EXPECT_EQ(from_physics.time, from_message.time);
  EXPECT_EQ(from_physics.angles, from_message.angles);
  EXPECT_EQ(from_physics.speeds, from_message.speeds);
  EXPECT_EQ(from_physics.sensor_values, from_message.sensor_values);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(from_physics.orientation[i], from_message.orientation[i]);
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(from_physics.com_velocity[i], from_message.com_velocity[i]);
  }
}

TEST_F(NnNodeTest, RepeatsTheAnswerToAStateSentAgain) {
  NnNode node = Make();
  const auto first = Send(node, State(0, 0.0));
  const auto again = Send(node, State(0, 0.0));
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].target, first[0].target);
  EXPECT_EQ(again[0].seq, first[0].seq);
  EXPECT_EQ(node.counters().states_repeated, 1);
}

TEST_F(NnNodeTest, ARobotOfAnotherJointCountStopsTheNode) {
  NnNode node = Make(4);
  EXPECT_TRUE(Send(node, State(0, 0.0, 6)).empty());
  EXPECT_NE(node.error().find("drives 4 joints but robot snake has 6"),
            std::string::npos)
      << node.error();
  EXPECT_TRUE(Send(node, State(1, 0.01, 4)).empty());
}

TEST_F(NnNodeTest, ForeignAndForgedStatesAreNotAnswered) {
  NnNode node = Make();
  robot_state_t other = State(0, 0.0);
  other.robot = "other";
  EXPECT_TRUE(Send(node, other).empty());
  robot_state_t forged = State(0, std::nan(""));
  EXPECT_TRUE(Send(node, forged).empty());
  robot_state_t lying = State(0, 0.0);
  lying.num_joints = 9;
  EXPECT_TRUE(Send(node, lying).empty());
  EXPECT_EQ(node.counters().states_foreign, 1);
  EXPECT_EQ(node.counters().messages_malformed, 2);
  EXPECT_TRUE(node.error().empty());
}

}  // namespace
}  // namespace mrsim

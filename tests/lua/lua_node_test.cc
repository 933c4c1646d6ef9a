// mrsim-lua's node in process with a fake clock: it answers states with the
// script's targets, repeats lost answers, keeps the rate, and stops with
// the script's line when the script fails.
#include "lua_controller/process/lua_node.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "lcmtypes/runtime/channels.h"
#include "lua_controller/lua_templates.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/scenario/sensor_kind.h"

namespace mrsim {
namespace {

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

const char* kRamp =
    "function step(t, state)\n"
    "  local out = {}\n"
    "  for i = 1, state.n do\n"
    "    out[i] = state.axes[i] == 'yaw' and -t or t\n"
    "  end\n"
    "  return out\n"
    "end\n";

class LuaNodeTest : public ::testing::Test {
 protected:
  std::unique_ptr<LuaNode> Make(const std::string& source, double rate = 0) {
    LuaNodeOptions o;
    o.robot = "snake";
    o.sender = "lua-snake";
    o.rate = rate;
    return std::make_unique<LuaNode>(
        o, std::make_unique<LuaScript>(source, "ctl.lua"),
        [](int n) {
          std::vector<Axis> axes;
          for (int i = 0; i < n; ++i)
            axes.push_back(i % 2 ? Axis::kYaw : Axis::kPitch);
          return axes;
        },
        now_);
  }
  std::vector<joint_command_t> Send(LuaNode& node, const robot_state_t& s) {
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
  LuaOutbox out_;
};

TEST_F(LuaNodeTest, AnswersEachStateWithTheScriptsTargets) {
  auto node = Make(kRamp);
  for (int k = 0; k < 5; ++k) {
    const auto got = Send(*node, State(k, k * 0.01));
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].state_seq, k);
    EXPECT_EQ(got[0].sender, "lua-snake");
    EXPECT_EQ(got[0].target,
              (std::vector<double>{k * 0.01, -k * 0.01, k * 0.01, -k * 0.01}));
  }
  EXPECT_EQ(node->counters().states_answered, 5);
  EXPECT_TRUE(node->error().empty());
}

TEST_F(LuaNodeTest, ScriptSeesTheRobotsOrientationAndHeading) {
  auto node = Make(
      "function step(t, state)\n"
      "  local q = state.orientation\n"
      "  return {state.heading, q[1], q[2], q[4]}\n"
      "end\n");
  robot_state_t s = State(0, 0);
  s.orientation[0] = std::cos(M_PI / 4);  // w: turned 90 degrees about z
  s.orientation[3] = std::sin(M_PI / 4);
  s.heading = M_PI / 2;
  const auto got = Send(*node, s);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].target, (std::vector<double>{M_PI / 2, std::cos(M_PI / 4),
                                                0.0, std::sin(M_PI / 4)}));
}

// Every kind of SensorKinds(), so a kind added later must reach Lua too: a
// sensor module carrying two of the kind (faces 2 and 5, values 10k + c) as
// the simulator encodes it; the script returns what it finds under the
// kind's name in by_kind and in readings, and the faces.
TEST_F(LuaNodeTest, ScriptReadsEverySensorKindByName) {
  for (const SensorKind& kind : SensorKinds()) {
    SCOPED_TRACE(kind.name);
    // A camera's pictures are no reading of the state.
    if (kind.read == nullptr) continue;
    const int channels = static_cast<int>(kind.channels.size());
    ASSERT_GT(channels, 0);
    // The force plate is one per module, on no face; others two.
    const bool one = kind.store != nullptr && !kind.many;
    const std::vector<int> faces =
        one ? std::vector<int>{-1} : std::vector<int>{2, 5};
    RobotState state;
    state.robot = "snake";
    state.time = 0.25;
    state.joints.resize(faces.size() * (channels + 1) + 1);
    SensorModuleState& sm = state.sensor_modules.emplace_back();
    for (size_t k = 0; k < faces.size(); ++k) {
      std::vector<double> values;
      for (int c = 0; c < channels; ++c) values.push_back(10.0 * k + c + 1);
      if (kind.store != nullptr) {
        kind.store(sm, faces[k], values);
      } else {
        sm.readings.push_back({kind.name, faces[k], values});
      }
    }
    const std::string kind_name = kind.name;
    auto node = Make(
        "function step(t, state)\n"
        "  local out = {}\n"
        "  local mine = state.sensors[1].by_kind['" +
        kind_name +
        "']\n"
        "  for _, r in ipairs(mine) do\n"
        "    out[#out + 1] = r.face\n"
        "    for _, v in ipairs(r.values) do out[#out + 1] = v end\n"
        "  end\n"
        "  local listed = 0\n"
        "  for _, r in ipairs(state.sensors[1].readings) do\n"
        "    if r.kind == '" +
        kind_name +
        "' then listed = listed + 1 end\n"
        "  end\n"
        "  out[#out + 1] = listed\n"
        "  while #out < state.n do out[#out + 1] = 0 end\n"
        "  return out\n"
        "end\n");
    const auto got = Send(*node, ToRobotStateMessage(state, /*seq=*/1));
    ASSERT_EQ(got.size(), 1u) << node->error();
    std::vector<double> want;
    for (size_t k = 0; k < faces.size(); ++k) {
      want.push_back(faces[k]);
      for (int c = 0; c < channels; ++c) want.push_back(10.0 * k + c + 1);
    }
    want.push_back(static_cast<double>(faces.size()));
    want.resize(state.joints.size(), 0.0);
    EXPECT_EQ(got[0].target, want);
  }
}

TEST_F(LuaNodeTest, RepeatedStateGetsTheSameAnswerAndForeignOnesNone) {
  auto node = Make(kRamp);
  const auto first = Send(*node, State(7, 0.5));
  const auto again = Send(*node, State(7, 0.5));
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].target, first[0].target);
  EXPECT_EQ(again[0].seq, first[0].seq);
  robot_state_t other = State(8, 0.51);
  other.robot = "other";
  EXPECT_TRUE(Send(*node, other).empty());
  EXPECT_EQ(node->counters().states_repeated, 1);
  EXPECT_EQ(node->counters().states_foreign, 1);
}

TEST_F(LuaNodeTest, RateSkipsStatesUntilLockstepSendsOneAgain) {
  auto node = Make(kRamp, 50);  // every 0.02 s
  EXPECT_EQ(Send(*node, State(0, 0.00)).size(), 1u);
  EXPECT_TRUE(Send(*node, State(1, 0.01)).empty());
  EXPECT_EQ(Send(*node, State(2, 0.02)).size(), 1u);
  EXPECT_TRUE(Send(*node, State(3, 0.03)).empty());
  // Lockstep waits for seq 3: the node answers it and every later state.
  EXPECT_EQ(Send(*node, State(3, 0.03)).size(), 1u);
  EXPECT_EQ(Send(*node, State(4, 0.04)).size(), 1u);
}

TEST_F(LuaNodeTest, ScriptErrorStopsTheNodeWithItsLine) {
  auto node = Make(
      "function step(t, state)\n"
      "  if t > 0.015 then error('too late') end\n"
      "  return {0, 0, 0, 0}\n"
      "end\n");
  EXPECT_EQ(Send(*node, State(0, 0.00)).size(), 1u);
  EXPECT_EQ(Send(*node, State(1, 0.01)).size(), 1u);
  EXPECT_TRUE(Send(*node, State(2, 0.02)).empty());
  EXPECT_NE(node->error().find("ctl.lua:2: too late"), std::string::npos)
      << node->error();
  EXPECT_TRUE(Send(*node, State(3, 0.03)).empty());
}

TEST_F(LuaNodeTest, WrongJointCountIsAnErrorNamingTheStepLine) {
  auto node = Make("\nfunction step() return {1} end");
  EXPECT_TRUE(Send(*node, State(0, 0)).empty());
  EXPECT_NE(node->error().find("ctl.lua:2:"), std::string::npos)
      << node->error();
}

TEST_F(LuaNodeTest, ForgedTimesAndJointCountsAreCountedAndDropped) {
  auto node = Make(kRamp);
  EXPECT_TRUE(Send(*node, State(0, std::nan(""))).empty());
  EXPECT_TRUE(Send(*node, State(1, 2e9)).empty());
  robot_state_t lying = State(2, 0.1);
  lying.num_joints = 9;
  EXPECT_TRUE(Send(*node, lying).empty());
  EXPECT_EQ(node->counters().messages_malformed, 3);
  EXPECT_EQ(Send(*node, State(3, 0.2)).size(), 1u);
}

TEST_F(LuaNodeTest, PrintedLinesReachTheLog) {
  auto node = Make("function step(t, s) print('t=' .. t) return {0,0,0,0} end");
  Send(*node, State(0, 0.5));
  const auto log = node->TakeLog();
  ASSERT_FALSE(log.empty());
  EXPECT_EQ(log.back(), "print: t=0.5");
}

// A script that defines on_gait_command takes steering: mrsim-lua says so
// with a gait status (at once, then each second), hands each command to
// the script and acknowledges its verdict, so the studio and mrsim-ctl
// steer it as they steer mrsim-gait. A script without it sends nothing.
TEST_F(LuaNodeTest, AScriptWithOnGaitCommandTakesSteeringAndSaysSo) {
  const auto statuses = [&] {
    std::vector<gait_status_t> got;
    for (auto& [channel, msg] : out_.messages) {
      if (const auto* st = std::get_if<gait_status_t>(&msg)) {
        EXPECT_EQ(channel, GaitStatusChannel("MRSIM", "snake"));
        got.push_back(*st);
      }
    }
    out_.clear();
    return got;
  };
  auto plain = Make(kRamp);
  EXPECT_FALSE(plain->takes_gait_commands());
  plain->Tick(now_, &out_);
  Send(*plain, State(0, 0.0));
  plain->Tick(AfterSeconds(now_, 2), &out_);
  EXPECT_TRUE(statuses().empty());

  auto node = Make(
      "speed = 0\n"
      "function on_gait_command(cmd)\n"
      "  if cmd.motion == 'roll' then return false, 'I do not roll' end\n"
      "  if cmd.motion == 'forward' then speed = cmd.strength end\n"
      "end\n"
      "function step(t, state)\n"
      "  local out = {}\n"
      "  for i = 1, state.n do out[i] = speed end\n"
      "  return out\n"
      "end\n");
  ASSERT_TRUE(node->takes_gait_commands());
  node->Tick(now_, &out_);
  auto said = statuses();
  ASSERT_EQ(said.size(), 1u);  // the heartbeat: it takes steering
  EXPECT_EQ(said[0].robot, "snake");
  EXPECT_EQ(said[0].kind, "lua");

  gait_command_t c{};
  c.robot = "snake";
  c.sender = "studio";
  c.seq = 7;
  c.motion = "forward";
  c.strength = 0.5;
  node->OnGaitCommand(c, now_, &out_);
  said = statuses();
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].command_seq, 7);
  EXPECT_EQ(said[0].command_sender, "studio");
  EXPECT_EQ(said[0].command_result, int8_t{gait_status_t::APPLIED});
  EXPECT_EQ(said[0].motion, "forward");
  const auto answer = Send(*node, State(0, 0.0));
  ASSERT_EQ(answer.size(), 1u);
  EXPECT_EQ(answer[0].target[0], 0.5);  // the script steered

  c.seq = 8;
  c.motion = "roll";
  node->OnGaitCommand(c, now_, &out_);
  said = statuses();
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].command_result, int8_t{gait_status_t::REJECTED});
  EXPECT_EQ(said[0].command_error, "I do not roll");
  c.seq = 9;
  c.motion = "forward";
  c.strength = 2;  // out of range: refused before the script sees it
  node->OnGaitCommand(c, now_, &out_);
  said = statuses();
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].command_result, int8_t{gait_status_t::REJECTED});
  EXPECT_EQ(node->counters().commands_applied, 1);
  EXPECT_EQ(node->counters().commands_rejected, 2);

  // The heartbeat each second, not more often.
  node->Tick(AfterSeconds(now_, 0.5), &out_);
  EXPECT_TRUE(statuses().empty());
  node->Tick(AfterSeconds(now_, 1.1), &out_);
  said = statuses();
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(said[0].running);
  EXPECT_EQ(said[0].states_answered, 1);
}

// The serpenoid template a student starts from is steerable: stop halts
// its wave, forward starts it again.
TEST_F(LuaNodeTest, TheSerpenoidTemplateStopsAndGoesWhenSteered) {
  const auto& templates = LuaTemplates();
  const auto it =
      std::find_if(templates.begin(), templates.end(),
                   [](const LuaTemplate& t) { return t.name == "serpenoid"; });
  ASSERT_NE(it, templates.end());
  auto node = Make(it->source);
  ASSERT_TRUE(node->takes_gait_commands());
  const auto pitch_swing = [&](int64_t seq, double t) {
    const auto answer = Send(*node, State(seq, t));
    double swing = 0;
    for (size_t i = 0; i < answer.at(0).target.size(); i += 2) {
      swing = std::max(swing, std::abs(answer.at(0).target[i]));
    }
    return swing;
  };
  EXPECT_GT(pitch_swing(0, 2.0), 0.1);
  gait_command_t c{};
  c.seq = 1;
  c.motion = "stop";
  node->OnGaitCommand(c, now_, &out_);
  out_.clear();
  EXPECT_EQ(pitch_swing(1, 2.1), 0.0);
  c.seq = 2;
  c.motion = "forward";
  c.strength = 1;
  node->OnGaitCommand(c, now_, &out_);
  out_.clear();
  EXPECT_GT(pitch_swing(2, 2.2), 0.1);
  EXPECT_EQ(node->counters().commands_applied, 2);
}

TEST_F(LuaNodeTest, ExitsWithASilentSimulator) {
  LuaNodeOptions o;
  o.robot = "snake";
  o.exit_with_sim = true;
  LuaNode node(
      o, std::make_unique<LuaScript>(kRamp, "ctl.lua"),
      [](int n) { return std::vector<Axis>(n, Axis::kPitch); }, now_);
  node.OnState(State(0, 0), now_, &out_);
  node.Tick(AfterSeconds(now_, 1), &out_);
  EXPECT_FALSE(node.done());
  node.Tick(AfterSeconds(now_, LuaNode::kSimulatorSilence + 0.1), &out_);
  EXPECT_TRUE(node.done());
  EXPECT_FALSE(node.gave_up());
}

}  // namespace
}  // namespace mrsim

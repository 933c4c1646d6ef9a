// mrsim-gait's node in process with a fake clock: answers, repeats,
// resets, rate, queued and bad gait commands, the gait status and its
// heartbeat, keyboard commands, motion warnings; command parsing; axes.
#include "gait_controller/process/gait_node.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "gait_controller/gait_presets.h"
#include "gait_controller/process/gait_command_apply.h"
#include "gait_controller/process/joint_axes_spec.h"
#include "gait_controller/process/key_command.h"
#include "lcmtypes/runtime/channels.h"

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

class GaitNodeTest : public ::testing::Test {
 protected:
  std::unique_ptr<GaitNode> Make(double rate = 100.0,
                                 const std::string& axes = "pitch") {
    GaitNodeOptions o;
    o.robot = "snake";
    o.sender = "g";
    o.rate = rate;
    auto node = std::make_unique<GaitNode>(
        o, [axes](int n) { return JointAxesSpec(axes).Expand(n); },
        *FindGaitPreset("forward"), now_);
    node->Start(now_, &out_);
    Collect();
    return node;
  }
  void Collect() {
    for (auto& [channel, msg] : out_.messages) {
      if (auto* c = std::get_if<joint_command_t>(&msg)) {
        EXPECT_EQ(channel, CommandChannel("MRSIM", "snake"));
        got_.push_back(*c);
      } else {
        EXPECT_EQ(channel, GaitStatusChannel("MRSIM", "snake"));
        statuses_.push_back(std::get<gait_status_t>(msg));
      }
    }
    out_.clear();
  }
  void Send(GaitNode& node, const robot_state_t& s) {
    node.OnState(s, now_, &out_);
    Collect();
  }
  void SendGait(GaitNode& node, const gait_command_t& c) {
    node.OnGaitCommand(c, now_, &out_);
    Collect();
  }

  WallTime now_{};
  GaitOutbox out_;
  std::vector<joint_command_t> got_;
  std::vector<gait_status_t> statuses_;
};

TEST_F(GaitNodeTest, AnswersEachStateOnceWithTheControllersTargets) {
  auto node = Make();
  GaitController reference(std::vector<Axis>(4, Axis::kPitch));
  reference.SetGait(*FindGaitPreset("forward"));
  for (int k = 0; k < 200; ++k) {
    const double t = k * 0.01;
    Send(*node, State(k, t));
    // The clock is the states' sim time: dt is the difference of two.
    const auto& want = reference.Update(k == 0 ? 0.0 : t - (k - 1) * 0.01);
    ASSERT_EQ(got_.size(), static_cast<size_t>(k + 1));
    const joint_command_t& c = got_.back();
    EXPECT_EQ(c.state_seq, k);
    EXPECT_EQ(c.sender, "g");
    EXPECT_EQ(c.robot, "snake");
    EXPECT_EQ(c.target, want) << k;
  }
  EXPECT_EQ(node->counters().states_answered, 200);
}

TEST_F(GaitNodeTest, RepeatedStatesGetTheSameAnswersOlderAreIgnored) {
  auto node = Make();
  for (int k = 0; k < 150; ++k) Send(*node, State(k, k * 0.01));
  const joint_command_t last = got_.back();
  const joint_command_t before = got_[148];
  Send(*node, State(149, 1.49));
  ASSERT_EQ(got_.size(), 151u);
  EXPECT_EQ(got_.back().target, last.target);
  EXPECT_EQ(got_.back().seq, last.seq);
  // Pipelined lockstep re-sends the two states it waits for.
  Send(*node, State(148, 1.48));
  ASSERT_EQ(got_.size(), 152u);
  EXPECT_EQ(got_.back().target, before.target);
  EXPECT_EQ(got_.back().state_seq, 148);
  Send(*node, State(100, 1.0));
  EXPECT_EQ(got_.size(), 152u);
  EXPECT_EQ(node->counters().states_repeated, 2);
  EXPECT_EQ(node->counters().states_skipped, 1);
}

TEST_F(GaitNodeTest, SimTimeGoingBackRestartsFromRest) {
  auto node = Make();
  for (int k = 0; k < 150; ++k) Send(*node, State(k, k * 0.01));
  EXPECT_NE(got_.back().target, std::vector<double>(4, 0.0));
  Send(*node, State(150, 0.0));  // a reset: seq goes on, time starts again
  EXPECT_EQ(got_.back().target, std::vector<double>(4, 0.0));
}

TEST_F(GaitNodeTest, RateSkipsStatesThatComeTooOften) {
  auto node = Make(50.0);
  for (int k = 0; k < 100; ++k) Send(*node, State(k, k * 0.01));
  EXPECT_EQ(node->counters().states_answered, 50);
  EXPECT_EQ(node->counters().states_skipped, 50);
}

TEST_F(GaitNodeTest, SkippedStateSentAgainSwitchesToEveryState) {
  auto node = Make(50.0);
  Send(*node, State(0, 0.0));
  Send(*node, State(1, 0.01));  // skipped at 50 Hz
  EXPECT_EQ(got_.size(), 1u);
  Send(*node, State(1, 0.01));  // lockstep: the simulator waits for an answer
  ASSERT_EQ(got_.size(), 2u);
  EXPECT_EQ(got_.back().state_seq, 1);
  Send(*node, State(2, 0.02));
  EXPECT_EQ(got_.size(), 3u);
  bool noted = false;
  for (const auto& line : node->TakeLog()) {
    noted = noted || line.find("answering every state") != std::string::npos;
  }
  EXPECT_TRUE(noted);
}

// A paused realtime sim re-sends its newest state, which --rate may have
// skipped: that is no lockstep, and the rate still holds.
TEST_F(GaitNodeTest, ASkippedStateAPausedRealtimeSimSendsAgainStaysSkipped) {
  auto node = Make(50.0);
  sim_status_t status{};
  status.clock = "realtime";
  status.mode = sim_status_t::PAUSED;
  node->OnSimStatus(status, now_, &out_);
  Collect();
  Send(*node, State(0, 0.0));
  Send(*node, State(1, 0.01));  // skipped at 50 Hz
  Send(*node, State(1, 0.01));  // sent again while paused
  Send(*node, State(1, 0.01));
  EXPECT_EQ(got_.size(), 1u);
  Send(*node, State(2, 0.02));
  Send(*node, State(3, 0.03));  // still 50 Hz
  ASSERT_EQ(got_.size(), 2u);
  EXPECT_EQ(got_.back().state_seq, 2);
  for (const auto& line : node->TakeLog()) {
    EXPECT_EQ(line.find("answering every state"), std::string::npos) << line;
  }
}

TEST_F(GaitNodeTest, ExitWithSimEndsTheNodeWhenTheSimulatorStops) {
  GaitNodeOptions o;
  o.robot = "snake";
  o.sender = "g";
  for (bool exit_with_sim : {false, true}) {
    o.exit_with_sim = exit_with_sim;
    GaitNode node(
        o, [](int n) { return JointAxesSpec("pitch").Expand(n); },
        *FindGaitPreset("forward"), now_);
    sim_status_t status{};
    status.clock = "lockstep";
    status.mode = sim_status_t::RUNNING;
    node.OnSimStatus(status, now_, &out_);
    EXPECT_FALSE(node.done());
    status.mode = sim_status_t::STOPPING;
    node.OnSimStatus(status, now_, &out_);
    EXPECT_EQ(node.done(), exit_with_sim);
  }
}

// A simulator killed (or its host lost) sends no STOPPING: with
// --exit-with-sim the node stops after kSimulatorSilence without a word
// from it, and not before.
TEST_F(GaitNodeTest, ExitWithSimEndsTheNodeWhenTheSimulatorGoesSilent) {
  GaitNodeOptions o;
  o.robot = "snake";
  o.sender = "g";
  o.exit_with_sim = true;
  GaitNode node(
      o, [](int n) { return JointAxesSpec("pitch").Expand(n); },
      *FindGaitPreset("forward"), now_);
  // Not silence before it heard a simulator at all (a slow start).
  const double t0 = GaitNode::kNoSimulatorGiveUp - 1;
  node.Tick(AfterSeconds(now_, t0), &out_);
  EXPECT_FALSE(node.done());
  const double silence = GaitNode::kSimulatorSilence;
  node.OnState(State(0, 0.0), AfterSeconds(now_, t0), &out_);
  node.Tick(AfterSeconds(now_, t0 + silence - 1), &out_);
  EXPECT_FALSE(node.done());
  sim_status_t status{};
  status.mode = sim_status_t::PAUSED;  // paused still says so twice a second
  node.OnSimStatus(status, AfterSeconds(now_, t0 + silence - 1), &out_);
  node.Tick(AfterSeconds(now_, t0 + 2 * silence - 2), &out_);
  EXPECT_FALSE(node.done());
  node.Tick(AfterSeconds(now_, t0 + 2 * silence - 1), &out_);
  EXPECT_TRUE(node.done());
  EXPECT_FALSE(node.gave_up());
  std::string log;
  for (const auto& line : node.TakeLog()) log += line + "\n";
  EXPECT_NE(log.find("silent for 5 s"), std::string::npos) << log;
}

// `mrsim-sim ... & mrsim-gait --exit-with-sim` with a simulator that failed
// to start used to wait forever; it gives up after kNoSimulatorGiveUp, and
// without --exit-with-sim it keeps waiting (a simulator started later).
TEST_F(GaitNodeTest, ExitWithSimGivesUpWhenNoSimulatorWasEverHeard) {
  GaitNodeOptions o;
  o.robot = "snake";
  o.sender = "g";
  for (bool exit_with_sim : {false, true}) {
    o.exit_with_sim = exit_with_sim;
    GaitNode node(
        o, [](int n) { return JointAxesSpec("pitch").Expand(n); },
        *FindGaitPreset("forward"), now_);
    node.Tick(AfterSeconds(now_, GaitNode::kNoSimulatorGiveUp - 0.5), &out_);
    EXPECT_FALSE(node.done());
    node.Tick(AfterSeconds(now_, GaitNode::kNoSimulatorGiveUp), &out_);
    EXPECT_EQ(node.done(), exit_with_sim);
    EXPECT_EQ(node.gave_up(), exit_with_sim);
    std::string log;
    for (const auto& line : node.TakeLog()) log += line + "\n";
    EXPECT_EQ(log.find("no simulator heard in 30 s") != std::string::npos,
              exit_with_sim)
        << log;
  }
}

// Lockstep under another name: the simulator's status says whom it waits
// for, and the node says how to match, once.
TEST_F(GaitNodeTest, ASimulatorWaitingForAnotherNameIsExplainedOnce) {
  GaitNodeOptions o;
  o.robot = "snake";
  o.sender = "gait-snake";
  GaitNode node(
      o, [](int n) { return JointAxesSpec("pitch").Expand(n); },
      *FindGaitPreset("forward"), now_);
  sim_status_t status{};
  status.clock = "lockstep";
  status.waiting_for = "gait-snake";  // us: nothing to say
  node.OnSimStatus(status, now_, &out_);
  EXPECT_TRUE(node.TakeLog().empty());
  status.waiting_for = "gait";
  node.OnSimStatus(status, now_, &out_);
  node.OnSimStatus(status, now_, &out_);
  const auto log = node.TakeLog();
  ASSERT_EQ(log.size(), 1u);
  EXPECT_NE(log[0].find("waiting for controller(s) 'gait', not for this one "
                        "('gait-snake')"),
            std::string::npos)
      << log[0];
  EXPECT_NE(log[0].find("--name gait"), std::string::npos) << log[0];
}

// A wrong --prefix or --lcm-url: said once, naming the channels listened
// to, instead of waiting in silence.
TEST_F(GaitNodeTest, NothingFromASimulatorIsSaidOnceNamingTheChannels) {
  GaitNodeOptions o;
  o.robot = "snake";
  o.prefix = "MRSM";
  o.sender = "g";
  GaitNode node(
      o, [](int n) { return JointAxesSpec("pitch").Expand(n); },
      *FindGaitPreset("forward"), now_);
  node.Tick(AfterSeconds(now_, GaitNode::kNoSimulatorWarning - 1), &out_);
  EXPECT_TRUE(node.TakeLog().empty());
  node.Tick(AfterSeconds(now_, GaitNode::kNoSimulatorWarning), &out_);
  const auto log = node.TakeLog();
  ASSERT_EQ(log.size(), 1u);
  EXPECT_NE(log[0].find("nothing from a simulator after 5 s on "
                        "MRSM_STATE_snake or MRSM_SIM_STATUS"),
            std::string::npos)
      << log[0];
  node.Tick(AfterSeconds(now_, 60), &out_);
  EXPECT_TRUE(node.TakeLog().empty());
  EXPECT_FALSE(node.done());
}

TEST_F(GaitNodeTest, ForeignAndMalformedStatesAreCountedNotAnswered) {
  auto node = Make();
  robot_state_t other = State(0, 0);
  other.robot = "other";
  Send(*node, other);
  Send(*node, State(0, std::nan("")));
  node->OnMalformedState();
  Send(*node, State(1, 0.01));
  Send(*node, State(2, 0.02, 5));  // wrong joint count for this robot
  EXPECT_EQ(got_.size(), 1u);
  EXPECT_EQ(node->counters().states_foreign, 1);
  EXPECT_EQ(node->counters().messages_malformed, 3);
}

TEST_F(GaitNodeTest, AxesThatDoNotFitStopTheNode) {
  GaitNodeOptions o;
  o.robot = "snake";
  GaitNode node(
      o, [](int n) { return JointAxesSpec("PYP").Expand(n); },
      *FindGaitPreset("forward"), now_);
  Send(node, State(0, 0));
  EXPECT_NE(node.error().find("--axes lists 3 joints but the robot has 4"),
            std::string::npos)
      << node.error();
  EXPECT_TRUE(got_.empty());
}

TEST_F(GaitNodeTest, CommandsBeforeTheFirstStateAreQueuedAndAcknowledged) {
  auto node = Make();
  ASSERT_EQ(statuses_.size(), 1u);  // the start: mrsim-ctl waits for it
  EXPECT_FALSE(statuses_.back().running);
  gait_command_t c{};
  c.seq = 7;
  c.sender = "ctl-1";
  c.motion = "backward";
  c.strength = 1;
  SendGait(*node, c);
  EXPECT_EQ(node->controller(), nullptr);
  EXPECT_EQ(statuses_.back().command_seq, 7);
  EXPECT_EQ(statuses_.back().command_sender, "ctl-1");
  EXPECT_EQ(statuses_.back().command_result, int8_t{gait_status_t::QUEUED});
  // Shown as queued, not as the old gait alone, until it applies.
  EXPECT_EQ(statuses_.back().queued, "motion backward 1.00");
  EXPECT_NE(node->Describe().find("queued: motion backward 1.00"),
            std::string::npos)
      << node->Describe();
  const size_t before = statuses_.size();
  node->Tick(AfterSeconds(now_, 1.5), &out_);
  Collect();
  ASSERT_GT(statuses_.size(), before);
  EXPECT_EQ(statuses_.back().queued, "motion backward 1.00");
  Send(*node, State(0, 0));
  ASSERT_NE(node->controller(), nullptr);
  EXPECT_EQ(node->controller()->motion(), Motion::kBackward);
  EXPECT_EQ(node->counters().commands_applied, 1);
  EXPECT_EQ(statuses_.back().command_result, int8_t{gait_status_t::APPLIED});
  EXPECT_TRUE(statuses_.back().running);
  EXPECT_EQ(statuses_.back().motion, "backward");
  EXPECT_EQ(statuses_.back().queued, "");
}

TEST_F(GaitNodeTest, StatusSaysWhatRunsOnChangeAndEverySecond) {
  auto node = Make();
  Send(*node, State(0, 0));
  const size_t start = statuses_.size();
  // A thousand seconds of wall time: one heartbeat a second.
  for (int i = 0; i < 1000; ++i) {
    const WallTime due = node->Tick(now_, &out_);
    Collect();
    now_ = due;
  }
  node->Tick(now_, &out_);
  Collect();
  EXPECT_EQ(statuses_.size() - start, 1000u);
  EXPECT_EQ(statuses_.back().gait, "forward");
  EXPECT_EQ(statuses_.back().kind, "linear");
  EXPECT_EQ(statuses_.back().parameters[4], 4.0);  // T
  // A change is published at once, and so is a rejection with its reason.
  gait_command_t c{};
  c.seq = 1;
  c.gait = "forward-strong";
  SendGait(*node, c);
  EXPECT_EQ(statuses_.back().gait, "forward-strong");
  EXPECT_EQ(statuses_.back().parameters[0], 2.0);
  EXPECT_EQ(statuses_.back().command_result, int8_t{gait_status_t::APPLIED});
  c.seq = 2;
  c.gait = "moonwalk";
  SendGait(*node, c);
  EXPECT_EQ(statuses_.back().command_result, int8_t{gait_status_t::REJECTED});
  EXPECT_NE(statuses_.back().command_error.find("moonwalk"), std::string::npos);
  EXPECT_EQ(statuses_.back().gait, "forward-strong");
  c.seq = 3;
  c.gait = "";
  c.robot = "other";
  c.motion = "stop";
  SendGait(*node, c);
  EXPECT_EQ(statuses_.back().command_result, int8_t{gait_status_t::REJECTED});
  EXPECT_NE(statuses_.back().command_error.find("'other'"), std::string::npos);
  node->OnMalformedGait(now_, &out_);
  Collect();
  EXPECT_EQ(statuses_.back().messages_malformed, 1);
  EXPECT_EQ(statuses_.back().commands_rejected, 3);
}

TEST_F(GaitNodeTest, KeyboardSteeringIsPublishedLikeAnyCommand) {
  auto node = Make(100.0, "pitch-yaw");
  Send(*node, State(0, 0));
  bool quit = false, help = false;
  const auto left =
      KeyCommand({KeyCode::kLeft, 0}, node->controller(), &quit, &help);
  ASSERT_TRUE(left);
  node->Apply(*left, "keyboard", now_, &out_);
  Collect();
  EXPECT_EQ(statuses_.back().motion, "turn-left");
  EXPECT_EQ(statuses_.back().strength, 0.5);
  EXPECT_EQ(statuses_.back().warning, "");
  // Left again: sharper.
  node->Apply(
      *KeyCommand({KeyCode::kLeft, 0}, node->controller(), &quit, &help),
      "keyboard", now_, &out_);
  Collect();
  EXPECT_EQ(statuses_.back().strength, 0.75);
  EXPECT_FALSE(
      KeyCommand({KeyCode::kChar, 'q'}, node->controller(), &quit, &help));
  EXPECT_TRUE(quit);
}

TEST_F(GaitNodeTest, TurningARobotWithoutYawJointsIsWarnedAbout) {
  auto node = Make(100.0, "pitch");
  Send(*node, State(0, 0));
  node->TakeLog();
  gait_command_t c{};
  c.motion = "turn-left";
  c.strength = 1;
  SendGait(*node, c);
  EXPECT_NE(statuses_.back().warning.find("no yaw joints"), std::string::npos)
      << statuses_.back().warning;
  bool warned = false;
  for (const auto& line : node->TakeLog()) {
    warned = warned ||
             line.find("warning: robot snake: turn-left") != std::string::npos;
  }
  EXPECT_TRUE(warned);
  c.motion = "forward";
  SendGait(*node, c);
  EXPECT_EQ(statuses_.back().warning, "");
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

namespace mrsim {
namespace {

// The simulator's request and its acknowledgement, as the node sees them.
void SaveOrLoad(GaitNode& node, int8_t command, const std::string& path,
                double sim_time, int64_t seq, WallTime now, GaitOutbox* out) {
  sim_control_t request{};
  request.seq = seq;
  request.sender = "ctl";
  request.command = command;
  request.path = path;
  node.OnSimControl(request);
  sim_status_t ack{};
  ack.control_seq = seq;
  ack.control_sender = "ctl";
  ack.control_ok = true;
  ack.sim_time = sim_time;
  node.OnSimStatus(ack, now, out);
}

std::vector<std::vector<double>> Answers(GaitOutbox* out) {
  std::vector<std::vector<double>> targets;
  for (auto& [channel, msg] : out->messages) {
    if (auto* c = std::get_if<joint_command_t>(&msg)) {
      targets.push_back(c->target);
    }
  }
  out->clear();
  return targets;
}

TEST(GaitNodeCheckpoint, AFreshNodeResumesTheSavedGaitBitForBit) {
  const std::string dir = ::testing::TempDir();
  const std::string checkpoint = dir + "/gait_node_resume.ckpt";
  GaitNodeOptions o;
  o.robot = "snake";
  o.sender = "g";
  auto axes = [](int n) { return JointAxesSpec("pitch-yaw").Expand(n); };
  const WallTime now{};
  GaitOutbox out;
  GaitNode a(o, axes, *FindGaitPreset("forward"), now);
  for (int k = 0; k <= 100; ++k) {
    a.OnState(State(k, k * 0.01, 6), now, &out);
    if (k == 60) {  // a turn still ramping in when the checkpoint is taken
      gait_command_t turn{};
      turn.motion = "turn-left";
      turn.strength = 0.8;
      a.OnGaitCommand(turn, now, &out);
    }
  }
  out.clear();
  // The simulator saved at the state of t = 1.00 (answered already).
  SaveOrLoad(a, sim_control_t::SAVE_CHECKPOINT, checkpoint, 1.0, 1, now, &out);
  ASSERT_TRUE(std::ifstream(GaitCheckpointPath(checkpoint, "snake")).good());
  for (int k = 101; k <= 300; ++k) a.OnState(State(k, k * 0.01, 6), now, &out);
  const auto original = Answers(&out);

  // A fresh process, started with --resume, gets the sim's states from the
  // checkpoint on (a new simulator numbers them from 0 again).
  GaitNode b(o, axes, *FindGaitPreset("forward"), now);
  b.Resume(checkpoint);
  b.OnState(State(0, 1.0, 6), now, &out);
  for (int k = 101; k <= 300; ++k) {
    b.OnState(State(k - 100, k * 0.01, 6), now, &out);
  }
  const auto resumed = Answers(&out);
  ASSERT_EQ(resumed.size(), original.size() + 1);
  for (size_t i = 0; i < original.size(); ++i) {
    ASSERT_EQ(resumed[i + 1], original[i]) << i;
  }
  EXPECT_EQ(b.controller()->motion(), Motion::kTurnLeft);

  // LOAD_CHECKPOINT over LCM in the same process does the same.
  SaveOrLoad(a, sim_control_t::LOAD_CHECKPOINT, checkpoint, 1.0, 2, now, &out);
  out.clear();
  a.OnState(State(301, 1.0, 6), now, &out);
  for (int k = 101; k <= 300; ++k) {
    a.OnState(State(k + 201, k * 0.01, 6), now, &out);
  }
  const auto reloaded = Answers(&out);
  ASSERT_EQ(reloaded.size(), resumed.size());
  EXPECT_EQ(reloaded, resumed);

  GaitNode c(o, axes, *FindGaitPreset("forward"), now);
  EXPECT_THROW(c.Resume(dir + "/none.ckpt"), std::runtime_error);

  // A damaged time is named, not restored as 0.
  const std::string saved = GaitCheckpointPath(checkpoint, "snake");
  std::stringstream text;
  text << std::ifstream(saved).rdbuf();
  std::string damaged = text.str();
  const size_t at = damaged.find("sim_time ") + 9;
  damaged.replace(at, damaged.find('\n', at) - at, "0x1.0pq");
  std::ofstream(saved) << damaged;
  GaitNode d(o, axes, *FindGaitPreset("forward"), now);
  d.Resume(checkpoint);
  d.OnState(State(0, 1.0, 6), now, &out);
  std::string log;
  for (const auto& line : d.TakeLog()) log += line + "\n";
  EXPECT_NE(log.find("sim_time: expected a time, got '0x1.0pq'"),
            std::string::npos)
      << log;
}

}  // namespace
}  // namespace mrsim

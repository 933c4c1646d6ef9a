// SimNode in process with a fake clock: lockstep waiting, re-sends, late
// controllers, pipelining, pause/step, pacing, every counter. No sockets,
// no sleeps: the test decides what time it is.
#include "sim_core/sim_process/sim_node.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/scenario/chain_builder.h"
#include "tests/common/child_process.h"
#include "tests/sim_process/wave_law.h"

namespace mrsim::testing {
namespace {

Scenario Snake(int modules = 6) {
  Scenario scenario;
  ChainOptions chain;
  chain.name = "snake";
  chain.modules = modules;
  scenario.robots.push_back(MakeChain(chain));
  return scenario;
}

// A node, its clock and what it published.
class Driver {
 public:
  explicit Driver(SimOptions options, const Scenario& scenario = Snake())
      : node_(std::make_unique<Physics>(scenario), std::move(options), log_,
              now_) {
    node_.Start(now_, &out_);
    Collect();
  }

  SimNode& node() { return node_; }
  WallTime now() const { return now_; }
  void Advance(double seconds) { now_ = AfterSeconds(now_, seconds); }
  std::string log() const { return log_.str(); }

  // One Tick at the current time; returns its deadline.
  WallTime Tick() {
    const WallTime due = node_.Tick(now_, &out_);
    Collect();
    return due;
  }
  // Ticks, jumping the clock to each deadline, until pred() or `seconds`
  // of fake time have passed.
  bool RunUntil(const std::function<bool()>& pred, double seconds) {
    const WallTime end = AfterSeconds(now_, seconds);
    while (!pred()) {
      const WallTime due = Tick();
      if (pred()) return true;
      if (due > now_) now_ = std::min(due, end);
      if (now_ >= end) return pred();
    }
    return true;
  }
  void Command(const joint_command_t& cmd) {
    node_.OnCommand(cmd, CommandChannel(kDefaultChannelPrefix, cmd.robot),
                    now_);
  }
  sim_status_t Control(int8_t command, int32_t steps = 0,
                       const std::string& path = "",
                       const std::string& sender = "test") {
    sim_control_t msg{};
    msg.seq = ++control_seq_[sender];
    msg.sender = sender;
    msg.command = command;
    msg.steps = steps;
    msg.path = path;
    node_.OnControl(msg, now_, &out_);
    Collect();
    EXPECT_FALSE(statuses_.empty());
    EXPECT_EQ(statuses_.back().control_seq, msg.seq);
    EXPECT_EQ(statuses_.back().control_sender, sender);
    return statuses_.back();
  }

  // Every robot state published (re-sends included), in order.
  std::vector<robot_state_t> states_;
  std::vector<sim_status_t> statuses_;

 private:
  void Collect() {
    for (auto& [channel, msg] : out_.messages) {
      if (auto* s = std::get_if<robot_state_t>(&msg)) {
        EXPECT_EQ(channel, StateChannel(kDefaultChannelPrefix, s->robot));
        states_.push_back(*s);
      } else if (auto* st = std::get_if<sim_status_t>(&msg)) {
        statuses_.push_back(*st);
      }
    }
    out_.clear();
  }

  std::ostringstream log_;
  WallTime now_{};
  SimOutbox out_;
  SimNode node_;
  std::map<std::string, int64_t> control_seq_;
};

joint_command_t Answer(const robot_state_t& state, const std::string& sender,
                       int64_t seq) {
  joint_command_t cmd{};
  cmd.utime = state.utime;
  cmd.seq = seq;
  cmd.robot = state.robot;
  cmd.sender = sender;
  cmd.state_seq = state.seq;
  cmd.target = WaveTargets(state);
  cmd.num_joints = static_cast<int32_t>(cmd.target.size());
  return cmd;
}

SimOptions Lockstep(int delay = 0) {
  SimOptions o;
  o.clock = ClockMode::kLockstep;
  o.controllers = {"ctl"};
  o.actuation_delay = delay;
  return o;
}

// The closed loop in one process: the answer to state k acts from period
// k + delay.
RobotState InProcessRun(const Scenario& scenario, int periods, int delay) {
  Physics physics(scenario);
  const int steps =
      static_cast<int>(std::lround(1.0 / (100.0 * physics.timestep())));
  std::vector<std::vector<double>> answers;
  for (int k = 0; k < periods; ++k) {
    answers.push_back(
        WaveTargets(ToRobotStateMessage(physics.ReadRobotState(0), k)));
    if (k >= delay) physics.SetJointTargets(0, answers[k - delay]);
    physics.Step(steps);
  }
  return physics.ReadRobotState(0);
}

void ExpectSameState(const RobotState& a, const robot_state_t& b) {
  const robot_state_t am = ToRobotStateMessage(a, b.seq);
  EXPECT_EQ(am.sim_time, b.sim_time);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(am.com[k], b.com[k]);
  ASSERT_EQ(am.joints.size(), b.joints.size());
  for (size_t j = 0; j < am.joints.size(); ++j) {
    EXPECT_EQ(am.joints[j].angle, b.joints[j].angle) << j;
    EXPECT_EQ(am.joints[j].speed, b.joints[j].speed) << j;
  }
}

// Answers every new state at once, as a controller in another process
// would; returns the final state after `periods` periods.
robot_state_t DriveLockstep(Driver& d, int periods) {
  int64_t answered = -1;
  int64_t seq = 0;
  while (d.node().status().state_seq < periods) {
    const robot_state_t& s = d.states_.back();
    if (s.seq > answered) {
      d.Command(Answer(s, "ctl", ++seq));
      answered = s.seq;
    }
    d.Tick();
  }
  return d.states_.back();
}

TEST(SimNode, StrictLockstepIsTheInProcessLoopBitForBit) {
  Driver d(Lockstep(0));
  const robot_state_t last = DriveLockstep(d, 150);
  EXPECT_EQ(last.seq, 150);
  EXPECT_EQ(d.node().status().commands_applied, 150);
  EXPECT_EQ(d.node().states_resent(), 0);
  ExpectSameState(InProcessRun(Snake(), 150, 0), last);
  EXPECT_GT(std::abs(last.joints[0].angle), 1e-3);  // it really moved
}

TEST(SimNode, PipelinedLockstepIsTheDelayedInProcessLoopBitForBit) {
  Driver d(Lockstep(1));
  const robot_state_t last = DriveLockstep(d, 150);
  // Period 0 runs without an answer; each later one applies the answer to
  // the state before.
  EXPECT_EQ(d.node().status().commands_applied, 149);
  EXPECT_EQ(d.node().status().actuation_delay, 1);
  ExpectSameState(InProcessRun(Snake(), 150, 1), last);
  // And it is a different trajectory than strict lockstep.
  const robot_state_t strict =
      ToRobotStateMessage(InProcessRun(Snake(), 150, 0), last.seq);
  EXPECT_NE(strict.joints[0].angle, last.joints[0].angle);
}

TEST(SimNode, PipelinedStepsOnePeriodAheadThenWaitsForTheOlderAnswer) {
  Driver d(Lockstep(1));
  ASSERT_EQ(d.states_.size(), 1u);  // state 0
  d.Tick();                         // period 0 needs no answer
  ASSERT_EQ(d.states_.back().seq, 1);
  d.Tick();  // period 1 needs the answer to state 0
  EXPECT_EQ(d.states_.back().seq, 1);
  // The answer to state 1 alone does not release period 1...
  d.Command(Answer(d.states_.back(), "ctl", 1));
  d.Tick();
  EXPECT_EQ(d.states_.back().seq, 1);
  EXPECT_EQ(d.node().status().rejected_seq, 0);  // ...but is kept
  // ...the answer to state 0 does, though it came after state 1's (a
  // controller that missed state 0 answers its re-send late); then state
  // 1's answer, kept, releases period 2.
  d.Command(Answer(d.states_.front(), "ctl", 2));
  EXPECT_EQ(d.node().status().rejected_seq, 0);
  d.Tick();
  EXPECT_EQ(d.states_.back().seq, 2);
  d.Tick();
  EXPECT_EQ(d.states_.back().seq, 3);
  EXPECT_EQ(d.node().status().commands_applied, 2);
  // An answer to a state no longer awaited is stale.
  d.Command(Answer(d.states_.front(), "ctl", 3));
  EXPECT_EQ(d.node().status().rejected_seq, 1);
}

TEST(SimNode, DeeperPipelineKeepsAnswersThatArriveBeforeTheyAreAwaited) {
  // With a delay of 2 the first two periods need no answer, so the answer
  // to state 0 may arrive when state 1 is already out; it must be kept
  // for period 2, not dropped (which stalled the run for good).
  Driver d(Lockstep(2));
  const robot_state_t state0 = d.states_.back();
  d.Tick();
  ASSERT_EQ(d.states_.back().seq, 1);
  d.Command(Answer(state0, "ctl", 1));
  EXPECT_EQ(d.node().status().rejected_seq, 0);
  d.Tick();
  ASSERT_EQ(d.states_.back().seq, 2);
  d.Tick();  // period 2 applies the answer to state 0
  EXPECT_EQ(d.states_.back().seq, 3);
  EXPECT_EQ(d.node().status().commands_applied, 1);
}

TEST(SimNode, DeeperPipelineIsTheDelayedInProcessLoopBitForBit) {
  Driver d(Lockstep(2));
  const robot_state_t last = DriveLockstep(d, 150);
  EXPECT_EQ(d.node().status().commands_applied, 148);
  ExpectSameState(InProcessRun(Snake(), 150, 2), last);
}

TEST(SimNode, LateControllerIsWaitedForResentAndNamedForAnHour) {
  SimOptions o = Lockstep();
  o.controllers = {"a", "late"};
  Driver d(o);
  d.Command(Answer(d.states_.back(), "a", 1));
  // An hour of fake wall time passes in a blink: nothing advances.
  d.RunUntil([] { return false; }, 3600.1);
  EXPECT_EQ(d.node().status().state_seq, 0);
  EXPECT_EQ(d.node().physics().time(), 0.0);
  EXPECT_EQ(d.node().status().waiting_for, "late");
  // Sent again every 0.25 s, a warning every --lockstep-timeout (2 s).
  EXPECT_EQ(d.node().states_resent(), 3600 * 4);
  EXPECT_EQ(d.states_.size(), 1u + 3600 * 4);
  size_t warnings = 0;
  const std::string log = d.log();
  for (size_t at = log.find("controller(s) late"); at != std::string::npos;
       at = log.find("controller(s) late", at + 1)) {
    ++warnings;
  }
  EXPECT_EQ(warnings, 1800u);
  // The late one answers the re-sent state: the run goes on.
  d.Command(Answer(d.states_.back(), "late", 1));
  d.Tick();
  EXPECT_EQ(d.node().status().state_seq, 1);
  EXPECT_EQ(d.node().status().waiting_for, "");
  EXPECT_EQ(d.node().status().commands_applied, 1);  // one robot, last wins
  EXPECT_EQ(d.node().status().messages_dropped, 1);  // "a" was replaced
}

// A controller started under another name than --controllers lists is
// refused; the wait warning says so instead of only "still waiting".
TEST(SimNode, LockstepWaitNamesARefusedSender) {
  SimOptions o = Lockstep();
  o.controllers = {"gait"};
  Driver d(o);
  d.Command(Answer(d.states_.back(), "gait-snake", 1));
  d.RunUntil([] { return false; }, 2.1);
  EXPECT_EQ(d.node().status().state_seq, 0);
  EXPECT_NE(d.log().find("commands from 'gait-snake' are refused: not among "
                         "--controllers (gait)"),
            std::string::npos)
      << d.log();
}

// A second simulator left running on the same URL and prefix used to go
// unmentioned while both took every command: each warns once per other
// simulator, and its own statuses (looped back) are not another's.
TEST(SimNode, AnotherSimulatorOnTheChannelsIsWarnedOfOnce) {
  SimOptions o;
  o.instance = "hostA:100";
  Driver d(o);
  d.node().OnSimStatus(d.node().status());
  EXPECT_TRUE(d.node().other_simulators().empty());
  EXPECT_EQ(d.log().find("another simulator"), std::string::npos) << d.log();
  sim_status_t other = d.node().status();
  other.instance = "hostA:200";
  other.sim_time = 12.5;
  d.node().OnSimStatus(other);
  d.node().OnSimStatus(other);
  EXPECT_EQ(d.node().other_simulators(), std::set<std::string>{"hostA:200"});
  const std::string warning =
      "mrsim-sim: warning: another simulator (hostA:200, realtime clock, sim "
      "time 12.5 s) publishes on MRSIM_SIM_STATUS";
  const size_t first = d.log().find(warning);
  EXPECT_NE(first, std::string::npos) << d.log();
  EXPECT_EQ(d.log().find(warning, first + 1), std::string::npos) << d.log();
  EXPECT_EQ(d.node().status().instance, "hostA:100");
}

TEST(SimNode, LastListedControllerWinsWhateverTheOrder) {
  SimOptions o = Lockstep();
  o.controllers = {"first", "second"};
  Driver d(o);
  joint_command_t a = Answer(d.states_.back(), "first", 1);
  joint_command_t b = Answer(d.states_.back(), "second", 1);
  a.target.assign(a.target.size(), 0.5);
  b.target.assign(b.target.size(), -0.5);
  d.Command(b);
  d.Command(a);
  d.Tick();
  ASSERT_EQ(d.node().status().state_seq, 1);
  EXPECT_EQ(d.node().physics().joint_targets(0), b.target);
  EXPECT_EQ(d.node().status().commands_applied, 1);
}

TEST(SimNode, PauseStepResumeAndRefusals) {
  SimOptions o;
  o.clock = ClockMode::kRealtime;
  o.paused = true;
  Driver d(o);
  d.RunUntil([] { return false; }, 10.0);
  EXPECT_EQ(d.node().status().mode, int8_t{sim_status_t::PAUSED});
  EXPECT_EQ(d.node().status().state_seq, 0);
  // Heartbeat at about 2 Hz of wall time while paused.
  EXPECT_GE(d.statuses_.size(), 20u);
  EXPECT_LE(d.statuses_.size(), 22u);

  EXPECT_TRUE(d.Control(sim_control_t::STEP, 7).control_ok);
  d.RunUntil([&] { return d.node().status().mode == sim_status_t::PAUSED; },
             10.0);
  EXPECT_EQ(d.node().status().state_seq, 7);
  EXPECT_EQ(d.node().status().steps, 7 * d.node().steps_per_period());
  d.RunUntil([] { return false; }, 5.0);
  EXPECT_EQ(d.node().status().state_seq, 7);

  const sim_status_t refused = d.Control(sim_control_t::STEP, 0);
  EXPECT_FALSE(refused.control_ok);
  EXPECT_NE(refused.last_error.find("STEP"), std::string::npos);
  EXPECT_FALSE(d.Control(sim_control_t::SET_SPEED).control_ok);
  EXPECT_FALSE(d.Control(99).control_ok);

  EXPECT_TRUE(d.Control(sim_control_t::RESUME).control_ok);
  const double t7 = d.node().physics().time();
  d.RunUntil([] { return false; }, 1.0);
  // Realtime: one second of wall time is one second of sim time.
  EXPECT_NEAR(d.node().physics().time() - t7, 1.0, 0.011);
  EXPECT_EQ(d.Control(sim_control_t::PAUSE).mode, int8_t{sim_status_t::PAUSED});
  const double frozen = d.node().physics().time();
  d.RunUntil([] { return false; }, 3.0);
  EXPECT_EQ(d.node().physics().time(), frozen);
  EXPECT_TRUE(d.Control(sim_control_t::QUIT).control_ok);
  d.Tick();
  ASSERT_TRUE(d.node().stopped());
  EXPECT_EQ(*d.node().stopped(), StopReason::kQuit);
  EXPECT_EQ(d.statuses_.back().mode, int8_t{sim_status_t::STOPPING});
}

std::vector<uint8_t> Encoded(const robot_state_t& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

// A viewer started after the sim paused, or one that lost the state that
// ended a STEP, still gets the robot: the newest state goes again with each
// status, byte for byte what was published.
TEST(SimNode, PausedSendsTheNewestStateAgainWithEachStatus) {
  SimOptions o;
  o.clock = ClockMode::kRealtime;
  o.paused = true;
  Driver d(o);
  ASSERT_EQ(d.states_.size(), 1u);
  const std::vector<uint8_t> first = Encoded(d.states_[0]);
  d.RunUntil([] { return false; }, 2.0);
  EXPECT_GE(d.states_.size(), 4u);
  EXPECT_LE(d.states_.size(), 6u);
  for (const robot_state_t& s : d.states_) EXPECT_EQ(Encoded(s), first);

  EXPECT_TRUE(d.Control(sim_control_t::STEP, 3).control_ok);
  d.RunUntil([&] { return d.node().status().state_seq == 3; }, 1.0);
  ASSERT_EQ(d.states_.back().seq, 3);
  const std::vector<uint8_t> third = Encoded(d.states_.back());
  const size_t before = d.states_.size();
  d.RunUntil([] { return false; }, 2.0);
  ASSERT_GE(d.states_.size(), before + 3);
  for (size_t i = before; i < d.states_.size(); ++i) {
    EXPECT_EQ(Encoded(d.states_[i]), third) << i;
  }
  EXPECT_EQ(d.node().states_published(), 4);
  EXPECT_EQ(d.node().states_resent(),
            static_cast<int64_t>(d.states_.size()) - 4);
}

// Lockstep, paused: the state awaited goes again, and a controller that
// answers each copy with its same command gets no rejection for it.
TEST(SimNode, PausedLockstepResendsTheAwaitedStateAndTakesRepeatedAnswers) {
  SimOptions o = Lockstep(0);
  o.paused = true;
  Driver d(o);
  ASSERT_EQ(d.states_.size(), 1u);
  const joint_command_t answer = Answer(d.states_[0], "ctl", 1);
  size_t answered = 0;
  d.RunUntil(
      [&] {
        for (; answered < d.states_.size(); ++answered) d.Command(answer);
        return false;
      },
      2.0);
  EXPECT_GE(d.states_.size(), 4u);
  for (const robot_state_t& s : d.states_) EXPECT_EQ(s.seq, 0);
  EXPECT_EQ(d.node().status().commands_rejected, 0);
  EXPECT_EQ(d.node().status().messages_dropped, 0);
  EXPECT_NE(d.node().Summary().find(std::to_string(d.states_.size() - 1) +
                                    " repeats ignored"),
            std::string::npos)
      << d.node().Summary();
  // The answer taken while paused drives the first period.
  EXPECT_TRUE(d.Control(sim_control_t::STEP, 1).control_ok);
  d.RunUntil([&] { return d.node().status().state_seq == 1; }, 1.0);
  EXPECT_EQ(d.node().status().commands_applied, 1);
}

TEST(SimNode, RealtimePacesPeriodsAndDoesNotBurstAfterALag) {
  SimOptions o;
  o.clock = ClockMode::kRealtime;
  o.speed = 2.0;
  Driver d(o);
  // Period k is due at k * period / speed.
  while (d.node().status().state_seq < 10) {
    const WallTime due = d.Tick();
    if (due > d.now()) d.Advance(SecondsBetween(d.now(), due));
  }
  EXPECT_NEAR(SecondsBetween(WallTime{}, d.now()), 9 * 0.01 / 2, 1e-6);
  // A stall of 3 s: the node re-anchors instead of running 600 periods
  // back to back.
  const int64_t before = d.node().status().state_seq;
  d.Advance(3.0);
  d.Tick();
  d.Tick();
  EXPECT_EQ(d.node().status().state_seq, before + 1);
}

TEST(SimNode, EveryRejectIsCountedExactlyAndMovesNothing) {
  SimOptions o;
  o.clock = ClockMode::kFast;
  o.paused = true;
  Driver d(o);
  const int joints = d.node().physics().joint_count(0);
  int64_t seq = 0;
  auto cmd = [&](std::string robot, std::vector<double> t, int64_t state) {
    joint_command_t c{};
    c.seq = ++seq;
    c.robot = std::move(robot);
    c.sender = "x";
    c.state_seq = state;
    c.target = std::move(t);
    c.num_joints = static_cast<int32_t>(c.target.size());
    return c;
  };
  const std::vector<double> ok(joints, 0.3);
  d.Command(cmd("snake", std::vector<double>(joints - 1, 0.1), 0));
  std::vector<double> nan = ok, huge = ok;
  nan[1] = std::nan("");
  huge[0] = 4.0;
  d.Command(cmd("snake", nan, 0));
  d.Command(cmd("snake", huge, 0));
  joint_command_t ghost = cmd("ghost", ok, 0);
  joint_command_t mislabelled = cmd("ghost", ok, 0);
  seq -= 2;  // another sender's numbering
  ghost.sender = mislabelled.sender = "y";
  d.Command(ghost);
  d.node().OnCommand(mislabelled, CommandChannel("MRSIM", "snake"), d.now());
  d.Command(cmd("snake", ok, 999));  // a state never published
  d.node().OnMalformed("");
  const sim_status_t s = d.node().status();
  EXPECT_EQ(s.rejected_joint_count, 1);
  EXPECT_EQ(s.rejected_value, 2);
  EXPECT_EQ(s.rejected_robot, 2);
  EXPECT_EQ(s.rejected_seq, 1);
  EXPECT_EQ(s.rejected_sender, 0);
  EXPECT_EQ(s.commands_rejected, 6);
  EXPECT_EQ(s.messages_malformed, 1);
  EXPECT_EQ(s.messages_dropped, 0);
  // A good one, repeated: the first applies, the repeat is ignored and is
  // no rejection (a controller answering a re-sent state sends it again).
  const joint_command_t good = cmd("snake", ok, 0);
  d.Command(good);
  d.Command(good);
  EXPECT_EQ(d.node().status().rejected_seq, 1);
  EXPECT_EQ(d.node().status().commands_rejected, 6);
  EXPECT_NE(d.node().Summary().find("(1 repeats ignored)"), std::string::npos)
      << d.node().Summary();
  // Two more valid ones before the period: the first is replaced (dropped).
  d.Command(cmd("snake", ok, -1));
  seq += 5;  // five commands this sender numbered but never sent
  d.Command(cmd("snake", ok, -1));
  EXPECT_EQ(d.Control(sim_control_t::STEP, 1).control_ok, true);
  d.Tick();
  const sim_status_t after = d.node().status();
  EXPECT_EQ(after.commands_applied, 1);
  EXPECT_EQ(after.messages_dropped, 2 + 5);
  // The summary tells a loss from a newer command taking an older's place.
  EXPECT_NE(d.node().Summary().find(
                "dropped 7 (5 never arrived, 2 replaced by a newer one"),
            std::string::npos)
      << d.node().Summary();

  // Lockstep: a sender not listed, and an answer to an older state.
  Driver l(Lockstep());
  joint_command_t stranger = Answer(l.states_.back(), "stranger", 1);
  l.Command(stranger);
  l.Command(Answer(l.states_.back(), "ctl", 1));
  l.Tick();
  l.Command(Answer(l.states_.front(), "ctl", 2));  // answers state 0 again
  EXPECT_EQ(l.node().status().rejected_sender, 1);
  EXPECT_EQ(l.node().status().rejected_seq, 1);
}

TEST(SimNode, ControlRequestsFromManyShellRunsAreNoDrops) {
  SimOptions o;
  o.paused = true;
  Driver d(o);
  // Every mrsim-ctl run is its own sender starting at seq 1.
  for (int i = 0; i < 50; ++i) {
    d.Control(sim_control_t::PAUSE, 0, "", "mrsim-ctl-" + std::to_string(i));
  }
  EXPECT_EQ(d.node().status().messages_dropped, 0);
  // A sender that skips a number lost exactly that request.
  d.Control(sim_control_t::PAUSE, 0, "", "script");  // seq 1
  sim_control_t msg{};
  msg.sender = "script";
  msg.command = sim_control_t::PAUSE;
  msg.seq = 3;
  SimOutbox out;
  d.node().OnControl(msg, d.now(), &out);
  EXPECT_EQ(d.node().status().messages_dropped, 1);
}

TEST(SimNode, NoStateCountsNoStatePublished) {
  SimOptions o;
  o.clock = ClockMode::kFast;
  o.publish_state = false;
  o.duration = 1.0;
  Driver d(o);
  d.RunUntil([&] { return d.node().stopped().has_value(); }, 100.0);
  ASSERT_TRUE(d.node().stopped());
  EXPECT_EQ(*d.node().stopped(), StopReason::kDuration);
  EXPECT_TRUE(d.states_.empty());
  EXPECT_EQ(d.node().states_published(), 0);
  EXPECT_EQ(d.node().status().state_seq, 100);
  EXPECT_NE(d.node().Summary().find("states published 0;"), std::string::npos)
      << d.node().Summary();
  // With states: one per period plus the initial one.
  o.publish_state = true;
  Driver p(o);
  p.RunUntil([&] { return p.node().stopped().has_value(); }, 100.0);
  EXPECT_EQ(p.node().states_published(), 101);
  EXPECT_EQ(p.states_.size(), 101u);
}

TEST(SimNode, ResetAndCheckpointLoadRestartTheLockstepEpoch) {
  const std::string dir = TempDir("sim_node_checkpoint");
  const std::string path = dir + "/mid.ckpt";
  for (int delay : {0, 1}) {
    SCOPED_TRACE(delay);
    Driver d(Lockstep(delay));
    DriveLockstep(d, 40);
    EXPECT_TRUE(d.Control(sim_control_t::SAVE_CHECKPOINT, 0, path).control_ok);
    const robot_state_t original = DriveLockstep(d, 100);
    const sim_status_t loaded =
        d.Control(sim_control_t::LOAD_CHECKPOINT, 0, path);
    ASSERT_TRUE(loaded.control_ok) << loaded.last_error;
    EXPECT_NEAR(loaded.sim_time, 0.4, 1e-9);
    // seq goes on; the continuation is the same run (strict lockstep).
    const robot_state_t again = DriveLockstep(d, 161);
    EXPECT_EQ(again.sim_time, original.sim_time);
    if (delay == 0) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(again.com[k], original.com[k]);
    }
    const sim_status_t bad =
        d.Control(sim_control_t::LOAD_CHECKPOINT, 0, dir + "/missing.ckpt");
    EXPECT_FALSE(bad.control_ok);
    EXPECT_NE(bad.last_error.find("missing.ckpt"), std::string::npos);
    const sim_status_t reset = d.Control(sim_control_t::RESET);
    EXPECT_TRUE(reset.control_ok);
    EXPECT_EQ(reset.sim_time, 0.0);
    const robot_state_t fresh = DriveLockstep(d, 161 + 1 + 150);
    ExpectSameState(InProcessRun(Snake(), 150, delay), fresh);
  }
}

TEST(SimNode, LocksDetachAndAttachOnRequestAndStatesSayWhich) {
  Driver d(Lockstep());
  const robot_state_t& first = d.states_.back();
  ASSERT_EQ(first.num_locks, 5);  // six modules, five locks
  EXPECT_EQ(first.lock_names[2], "snake/lock2");
  for (bool attached : first.lock_attached) EXPECT_TRUE(attached);

  sim_control_t detach{};
  detach.seq = 1;
  detach.sender = "test";
  detach.command = sim_control_t::DETACH;
  detach.robot = "snake";
  detach.lock = "snake/lock2";
  SimOutbox out;
  d.node().OnControl(detach, d.now(), &out);
  EXPECT_TRUE(d.node().status().control_ok) << d.node().status().last_error;
  const robot_state_t cut = DriveLockstep(d, 100);
  ASSERT_EQ(cut.num_locks, 5);
  EXPECT_FALSE(cut.lock_attached[2]);
  EXPECT_TRUE(cut.lock_attached[1]);
  // The body really came apart: not the trajectory of the whole snake.
  const robot_state_t whole =
      ToRobotStateMessage(InProcessRun(Snake(), 100, 0), cut.seq);
  EXPECT_NE(whole.com[0], cut.com[0]);

  sim_control_t bad = detach;
  bad.seq = 2;
  bad.lock = "snake/lock9";
  d.node().OnControl(bad, d.now(), &out);
  EXPECT_FALSE(d.node().status().control_ok);
  EXPECT_NE(d.node().status().last_error.find("snake/lock9"), std::string::npos)
      << d.node().status().last_error;

  sim_control_t attach = detach;
  attach.seq = 3;
  attach.command = sim_control_t::ATTACH;
  d.node().OnControl(attach, d.now(), &out);
  EXPECT_TRUE(d.node().status().control_ok);
  const robot_state_t joined = DriveLockstep(d, 101);
  EXPECT_TRUE(joined.lock_attached[2]);
}

TEST(SimNode, DurationStopsAndWritesTheExitCheckpoint) {
  const std::string dir = TempDir("sim_node_exit");
  SimOptions o = Lockstep();
  o.duration = 0.5;
  o.checkpoint_on_exit = dir + "/end.ckpt";
  Driver d(o);
  DriveLockstep(d, 50);
  d.Tick();
  ASSERT_TRUE(d.node().stopped());
  EXPECT_EQ(*d.node().stopped(), StopReason::kDuration);
  const auto saved = LoadCheckpoint(dir + "/end.ckpt");
  EXPECT_EQ(saved->time(), d.node().physics().time());
  // Stop after the end changes nothing.
  SimOutbox out;
  d.node().Stop(StopReason::kSignal, d.now(), &out);
  EXPECT_EQ(*d.node().stopped(), StopReason::kDuration);
}

// mrsim-camera's answer: no targets, state_seq of the state it pictured.
joint_command_t EmptyAnswer(const robot_state_t& state,
                            const std::string& sender, int64_t seq) {
  joint_command_t cmd{};
  cmd.utime = state.utime;
  cmd.seq = seq;
  cmd.robot = state.robot;
  cmd.sender = sender;
  cmd.state_seq = state.seq;
  cmd.num_joints = 0;
  return cmd;
}

// Lockstep with a camera among --controllers: the simulator waits for the
// camera's answer too, and that answer moves nothing, so the run is the
// in-process loop of the real controller bit for bit.
TEST(SimNode, LockstepWaitsForAnEmptyAnswerThatMovesNothing) {
  SimOptions o = Lockstep();
  o.controllers = {"ctl", "mrsim-camera"};
  Driver d(o);
  d.Command(Answer(d.states_.back(), "ctl", 1));
  // Past --lockstep-timeout (2 s of fake time): the wait names who is late.
  d.RunUntil([] { return false; }, 2.1);
  EXPECT_EQ(d.node().status().state_seq, 0);
  EXPECT_EQ(d.node().status().waiting_for, "mrsim-camera");
  int64_t ctl_seq = 1, camera_seq = 0;
  d.Command(EmptyAnswer(d.states_.back(), "mrsim-camera", ++camera_seq));
  d.Tick();
  ASSERT_EQ(d.node().status().state_seq, 1);
  int64_t answered = 0;
  while (d.node().status().state_seq < 150) {
    const robot_state_t& s = d.states_.back();
    if (s.seq > answered) {
      // The camera answers first or last: the same run either way.
      if (s.seq % 2 == 0) {
        d.Command(EmptyAnswer(s, "mrsim-camera", ++camera_seq));
      }
      d.Command(Answer(s, "ctl", ++ctl_seq));
      if (s.seq % 2 == 1) {
        d.Command(EmptyAnswer(s, "mrsim-camera", ++camera_seq));
      }
      answered = s.seq;
    }
    d.Tick();
  }
  ExpectSameState(InProcessRun(Snake(), 150, 0), d.states_.back());
  const sim_status_t s = d.node().status();
  EXPECT_EQ(s.commands_applied, 150);
  EXPECT_EQ(s.commands_rejected, 0);
  EXPECT_EQ(s.messages_dropped, 0);  // the camera replaced nothing
  EXPECT_NE(d.node().Summary().find("(150 answers without targets)"),
            std::string::npos)
      << d.node().Summary();
}

// The camera as the only lockstep party: the robot keeps its targets.
TEST(SimNode, AnEmptyAnswerAloneKeepsTheTargets) {
  SimOptions o = Lockstep();
  o.controllers = {"mrsim-camera"};
  Driver d(o);
  const std::vector<double> before = d.node().physics().joint_targets(0);
  for (int64_t k = 1; k <= 5; ++k) {
    joint_command_t cmd = EmptyAnswer(d.states_.back(), "mrsim-camera", k);
    // num_joints decides: lcm-gen's decode into a reused message leaves
    // the previous command's targets behind when it is 0.
    if (k % 2 == 0) cmd.target.assign(5, 9.0);
    d.Command(cmd);
    d.Tick();
  }
  EXPECT_EQ(d.node().status().state_seq, 5);
  EXPECT_EQ(d.node().physics().joint_targets(0), before);
  EXPECT_EQ(d.node().status().commands_applied, 0);
  EXPECT_EQ(d.node().status().commands_rejected, 0);
}

// Realtime and fast wait for nobody: an empty answer is ignored, is no
// rejection, and does not make a controller's answer to an older state
// stale.
TEST(SimNode, OutsideLockstepAnEmptyAnswerIsIgnoredHarmlessly) {
  SimOptions o;
  o.clock = ClockMode::kFast;
  o.paused = true;
  Driver d(o);
  EXPECT_EQ(d.Control(sim_control_t::STEP, 2).control_ok, true);
  d.RunUntil([&] { return d.node().status().state_seq >= 2; }, 10);
  ASSERT_GE(d.states_.size(), 3u);
  const std::vector<double> before = d.node().physics().joint_targets(0);
  d.Command(EmptyAnswer(d.states_.back(), "mrsim-camera", 1));
  joint_command_t late = Answer(d.states_[1], "ctl", 1);
  late.target.assign(late.target.size(), 0.25);
  d.Command(late);
  EXPECT_EQ(d.Control(sim_control_t::STEP, 1).control_ok, true);
  d.Tick();
  const sim_status_t s = d.node().status();
  EXPECT_EQ(s.commands_rejected, 0);
  EXPECT_EQ(s.commands_applied, 1);
  EXPECT_NE(d.node().physics().joint_targets(0), before);
  // A command with some but not all targets is still refused.
  joint_command_t short_one = Answer(d.states_.back(), "ctl", 2);
  short_one.target.pop_back();
  short_one.num_joints = static_cast<int32_t>(short_one.target.size());
  d.Command(short_one);
  EXPECT_EQ(d.node().status().rejected_joint_count, 1);
}

}  // namespace
}  // namespace mrsim::testing

namespace mrsim::testing {
namespace {

// A snake and, 1 m beside it, a loose sensor module dropped from 0.2 m.
Scenario SnakeAndALooseModule() {
  Scenario s = Snake();
  SensorModule eye;
  eye.guid = "eye";
  eye.position = Eigen::Vector3d(0, 1.0, 0.2);
  eye.imu = Imu{};
  s.loose_sensor_modules.push_back(eye);
  return s;
}

std::vector<robot_state_t> LooseStates(const Driver& d) {
  std::vector<robot_state_t> loose;
  for (const robot_state_t& s : d.states_) {
    if (s.robot == kLooseOwnerName) loose.push_back(s);
  }
  return loose;
}

// The loose parts' state goes out on <prefix>_STATE_loose with every
// period's robot states (same seq and time), where the physics moved them,
// and again after a reset.
TEST(SimNode, LoosePartsStateIsPublishedEveryPeriodAndAfterReset) {
  Driver d(Lockstep(), SnakeAndALooseModule());
  DriveLockstep(d, 100);
  const std::vector<robot_state_t> loose = LooseStates(d);
  ASSERT_GE(loose.size(), 100u);
  std::map<int64_t, double> snake_time;
  for (const robot_state_t& s : d.states_) {
    if (s.robot == "snake") snake_time[s.seq] = s.sim_time;
  }
  for (const robot_state_t& s : loose) {
    ASSERT_EQ(snake_time.count(s.seq), 1u) << s.seq;
    EXPECT_EQ(snake_time[s.seq], s.sim_time);
    ASSERT_EQ(s.num_sensor_modules, 1);
    EXPECT_EQ(s.num_frames, 0);
  }
  EXPECT_NEAR(loose.front().sensor_modules[0].pose.position[2], 0.2, 1e-9);
  // After 1 s it lies on the ground.
  EXPECT_NEAR(loose.back().sensor_modules[0].pose.position[2], 0.025, 0.005);
  EXPECT_NEAR(loose.back().sensor_modules[0].pose.position[1], 1.0, 0.01);
  ASSERT_EQ(loose.back().sensor_modules[0].num_readings, 1);

  const size_t before = LooseStates(d).size();
  EXPECT_TRUE(d.Control(sim_control_t::RESET).control_ok);
  const std::vector<robot_state_t> after = LooseStates(d);
  ASSERT_GT(after.size(), before);
  EXPECT_EQ(after.back().sim_time, 0.0);
  EXPECT_NEAR(after.back().sensor_modules[0].pose.position[2], 0.2, 1e-9);
}

// A loose lock's state goes out with the loose parts' as a robot's locks
// go out with its state: a weak one is seen to break.
TEST(SimNode, LoosePartsStateCarriesTheirLocksAndABreak) {
  Scenario s = Snake();
  for (int f = 0; f < 2; ++f) {
    Frame frame;
    frame.guid = f == 0 ? "post" : "door";
    frame.position = Eigen::Vector3d(0.06 * f, 1.0, 1.0);
    frame.is_static = f == 0;
    s.loose_frames.push_back(frame);
  }
  Joint lock;
  lock.guid = "weld";
  lock.left_frame_guid = "post";
  lock.right_frame_guid = "door";
  lock.type = JointType::kLock;
  lock.break_force = 0.001;  // N: the door's weight breaks it
  s.loose_joints.push_back(lock);
  Driver d(Lockstep(), s);
  DriveLockstep(d, 100);
  const std::vector<robot_state_t> loose = LooseStates(d);
  ASSERT_FALSE(loose.empty());
  ASSERT_EQ(loose.front().num_locks, 1);
  EXPECT_EQ(loose.front().lock_names[0], "weld");
  ASSERT_EQ(loose.back().num_locks, 1);
  EXPECT_FALSE(loose.back().lock_attached[0]);
}

// The snake and, 1 m beside it, a static loose base with an arm on a
// loose hinge about the vertical: with a servo when `servo`.
Scenario SnakeAndALooseArm(bool servo) {
  Scenario s = Snake();
  const Eigen::Quaterniond up(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  for (int f = 0; f < 2; ++f) {
    Frame frame;
    frame.guid = f == 0 ? "base" : "arm";
    frame.position = Eigen::Vector3d(0.05 * f, 1.0, 0.3);
    frame.quat_rotation = up;
    frame.is_static = f == 0;
    s.loose_frames.push_back(frame);
  }
  Joint hinge;
  hinge.guid = "arm hinge";
  hinge.left_frame_guid = "base";
  hinge.right_frame_guid = "arm";
  hinge.servo = servo;
  s.loose_joints.push_back(hinge);
  return s;
}

joint_command_t LooseCommand(std::vector<double> targets, int64_t seq) {
  joint_command_t c{};
  c.seq = seq;
  c.robot = kLooseOwnerName;
  c.sender = "arm-ctl";
  c.state_seq = -1;
  c.target = std::move(targets);
  c.num_joints = static_cast<int32_t>(c.target.size());
  return c;
}

// <prefix>_COMMAND_loose drives the loose servos as a robot's command
// drives its hinges: one target per loose servo, applied from the next
// period, and the loose state shows the hinge turning there.
TEST(SimNode, LooseServosTakeTheirCommandsOnCommandLoose) {
  SimOptions o;
  o.clock = ClockMode::kFast;
  Driver d(o, SnakeAndALooseArm(true));
  d.Command(LooseCommand({0.5}, 1));
  ASSERT_TRUE(
      d.RunUntil([&] { return d.node().status().state_seq >= 100; }, 60));
  EXPECT_EQ(d.node().physics().loose_targets(), std::vector<double>{0.5});
  const sim_status_t s = d.node().status();
  EXPECT_EQ(s.commands_applied, 1);
  EXPECT_EQ(s.commands_rejected, 0);
  const robot_state_t last = LooseStates(d).back();
  ASSERT_EQ(last.num_joints, 1);
  EXPECT_NEAR(last.joints[0].angle, 0.5, 0.01);
  // The snake's targets are untouched.
  EXPECT_EQ(d.node().physics().joint_targets(0),
            std::vector<double>(d.node().physics().joint_count(0), 0.0));

  // A wrong count is counted and dropped, and the status says why.
  d.Command(LooseCommand({0.1, 0.2}, 2));
  EXPECT_EQ(d.node().status().rejected_joint_count, 1);
  EXPECT_NE(d.node().status().last_error.find(
                "COMMAND_loose: expected 1 targets (one per loose servo), "
                "got 2"),
            std::string::npos)
      << d.node().status().last_error;
  d.Tick();
  EXPECT_EQ(d.node().physics().loose_targets(), std::vector<double>{0.5});
}

// Lockstep: a controller that drives the loose servos answers the loose
// state too, and its answer applies like a robot's.
TEST(SimNode, LockstepAppliesAnAnswerToTheLooseState) {
  Driver d(Lockstep(), SnakeAndALooseArm(true));
  const robot_state_t loose = LooseStates(d).back();
  joint_command_t answer = LooseCommand({-0.3}, 1);
  answer.sender = "ctl";
  answer.state_seq = loose.seq;
  d.Command(answer);
  d.Command(Answer(d.states_.back(), "ctl", 2));  // and the snake's
  d.Tick();
  EXPECT_EQ(d.node().status().state_seq, 1);
  EXPECT_EQ(d.node().physics().loose_targets(), std::vector<double>{-0.3});
  EXPECT_EQ(d.node().status().commands_applied, 2);
}

// Loose hinges without a servo take no command: counted and dropped, with
// the reason in the status; no loose parts at all: an unknown robot.
TEST(SimNode, ACommandForPassiveLoosePartsIsDroppedSayingWhy) {
  SimOptions o;
  o.clock = ClockMode::kFast;
  o.paused = true;
  Driver d(o, SnakeAndALooseArm(false));
  d.Command(LooseCommand({0.5}, 1));
  EXPECT_EQ(d.node().status().rejected_joint_count, 1);
  EXPECT_EQ(d.node().status().commands_rejected, 1);
  EXPECT_NE(d.node().status().last_error.find("the loose parts have no servo"),
            std::string::npos)
      << d.node().status().last_error;

  Driver none(o);
  none.Command(LooseCommand({0.5}, 1));
  EXPECT_EQ(none.node().status().rejected_robot, 1);
  EXPECT_NE(none.node().status().last_error.find("no loose parts"),
            std::string::npos);
}

TEST(SimNode, NoLoosePartsNoLooseState) {
  Driver d(Lockstep());
  DriveLockstep(d, 5);
  EXPECT_TRUE(LooseStates(d).empty());
}

}  // namespace
}  // namespace mrsim::testing

// mrsim-sim as a real process on loopback multicast, driven by real
// controller processes and by the test over LCM.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "mrsim/joint_command_t.hpp"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/sim_process/sim_client.h"
#include "tests/sim_process/wave_law.h"

namespace mrsim::testing {
namespace {

constexpr double kRate = 100.0;

// Every number a state message carries about the robot's body, exactly.
void ExpectSameBody(const robot_state_t& a, const robot_state_t& b) {
  EXPECT_EQ(a.sim_time, b.sim_time);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (size_t i = 0; i < a.frames.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(a.frames[i].position[k], b.frames[i].position[k])
          << "frame " << i;
    }
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(a.frames[i].orientation[k], b.frames[i].orientation[k])
          << "frame " << i;
    }
  }
  ASSERT_EQ(a.joints.size(), b.joints.size());
  for (size_t i = 0; i < a.joints.size(); ++i) {
    EXPECT_EQ(a.joints[i].angle, b.joints[i].angle) << "joint " << i;
    EXPECT_EQ(a.joints[i].speed, b.joints[i].speed) << "joint " << i;
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.com[k], b.com[k]);
    EXPECT_EQ(a.com_velocity[k], b.com_velocity[k]);
  }
}

int StepsPerPeriod(const Physics& physics) {
  return static_cast<int>(std::lround(1.0 / (kRate * physics.timestep())));
}

// The same closed loop as sim + test_controller in lockstep, in one process:
// the answer to state k acts from period k + delay.
robot_state_t InProcessWaveRun(const std::string& scenario_path, int periods,
                               int delay = 0) {
  Physics physics(ReadScenarioFile(scenario_path));
  const int steps = StepsPerPeriod(physics);
  std::vector<std::vector<double>> answers;
  for (int k = 0; k < periods; ++k) {
    const robot_state_t msg = ToRobotStateMessage(physics.ReadRobotState(0), k);
    answers.push_back(WaveTargets(msg));
    if (k >= delay) physics.SetJointTargets(0, answers[k - delay]);
    physics.Step(steps);
  }
  return ToRobotStateMessage(physics.ReadRobotState(0), periods);
}

std::vector<std::string> SimArgs(const std::string& scenario, int port,
                                 std::vector<std::string> extra) {
  std::vector<std::string> args = {SimBinary(),      scenario, "--lcm-url",
                                   TestLcmUrl(port), "--rate", "100"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// Strict (delay 0) and pipelined (delay 1) lockstep with a controller in
// another process give exactly the in-process loop with the same delay,
// whether mrsim-sim's send thread spins (the default) or sleeps.
class SimProcessLockstep
    : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(SimProcessLockstep, ExternalControllerMatchesInProcessRun) {
  const auto [delay, spin] = GetParam();
  const std::string dir = TempDir("sim_lockstep_" + std::to_string(delay) +
                                  (spin ? "_spin" : "_sleep"));
  const std::string scenario = TestScenarioPath(dir);
  const int port = (delay == 0 ? 7600 : 7611) + (spin ? 0 : 2);
  std::vector<std::string> flags = {
      "--clock",    "lockstep", "--controllers",     "ctl",
      "--duration", "1.5",      "--actuation-delay", std::to_string(delay),
      "--paused"};
  if (!spin) flags.push_back("--no-spin");
  SimClient client(TestLcmUrl(port));
  ASSERT_TRUE(client.good());
  const int periods = 150;  // 1.5 s of sim time
  ChildProcess sim(SimArgs(scenario, port, flags), dir + "/sim.log");
  ChildProcess controller(
      {ControllerBinary(), "--lcm-url", TestLcmUrl(port), "--name", "ctl"},
      dir + "/controller.log");
  // Stepped in bursts the test's socket holds even when a loaded machine
  // leaves it unscheduled (the last state is sent once); the last STEP
  // reaches the duration.
  ASSERT_TRUE(client.WaitFor([&] { return client.status().has_value(); }, 10));
  ASSERT_TRUE(client.StepAndWait(periods - 1))
      << sim.Output() << client.Describe();
  ASSERT_TRUE(client.Control(sim_control_t::STEP, 1)) << sim.Output();
  // The last state and the final status are sent before the sim exits.
  ASSERT_TRUE(client.WaitFor(
      [&] {
        return client.status() &&
               client.status()->mode == sim_status_t::STOPPING &&
               client.last_state_seq() == periods;
      },
      60.0))
      << sim.Output();
  EXPECT_EQ(sim.Wait(5.0), 0) << sim.Output();

  ASSERT_EQ(client.states().size(), 1u);
  const robot_state_t& external = client.states().begin()->second;
  EXPECT_EQ(external.seq, periods);
  EXPECT_EQ(client.status()->commands_applied, periods - delay) << sim.Output();
  EXPECT_EQ(client.status()->actuation_delay, delay);
  const robot_state_t internal = InProcessWaveRun(scenario, periods, delay);
  ExpectSameBody(external, internal);
  // The controller really moved the snake (the comparison is not trivial).
  EXPECT_GT(std::abs(internal.joints[0].angle), 1e-3);
  EXPECT_NE(sim.Output().find("mrsim-sim: stopped (duration reached)"),
            std::string::npos)
      << sim.Output();
  EXPECT_NE(sim.Output().find("states published 151"), std::string::npos)
      << sim.Output();
}

INSTANTIATE_TEST_SUITE_P(
    StrictAndPipelined, SimProcessLockstep,
    ::testing::Combine(::testing::Values(0, 1), ::testing::Bool()),
    [](const ::testing::TestParamInfo<std::tuple<int, bool>>& info) {
      return "Delay" + std::to_string(std::get<0>(info.param)) +
             (std::get<1>(info.param) ? "Spin" : "Sleep");
    });

TEST(SimProcess, CheckpointOverLcmContinuesIdentically) {
  const std::string dir = TempDir("sim_checkpoint");
  const std::string scenario = TestScenarioPath(dir);
  const int port = 7602;
  const std::string checkpoint = dir + "/mid.ckpt";
  robot_state_t original, loaded_once, loaded_twice;
  {
    SimClient client(TestLcmUrl(port));
    ChildProcess sim(
        SimArgs(scenario, port,
                {"--clock", "lockstep", "--controllers", "ctl", "--paused"}),
        dir + "/sim.log");
    ChildProcess controller(
        {ControllerBinary(), "--lcm-url", TestLcmUrl(port), "--name", "ctl"},
        dir + "/controller.log");
    ASSERT_TRUE(
        client.WaitFor([&] { return client.status().has_value(); }, 10));
    ASSERT_TRUE(client.StepAndWait(40))
        << sim.Output() << client.Describe() << "\n"
        << controller.Output();
    auto saved =
        client.Control(sim_control_t::SAVE_CHECKPOINT, 0, 0, checkpoint);
    ASSERT_TRUE(saved);
    ASSERT_TRUE(saved->control_ok) << saved->last_error;
    ASSERT_TRUE(std::filesystem::exists(checkpoint));

    ASSERT_TRUE(client.StepAndWait(60)) << sim.Output();
    original = client.states().begin()->second;
    EXPECT_NEAR(original.sim_time, 1.0, 1e-9);

    for (robot_state_t* out : {&loaded_once, &loaded_twice}) {
      auto loaded =
          client.Control(sim_control_t::LOAD_CHECKPOINT, 0, 0, checkpoint);
      ASSERT_TRUE(loaded);
      ASSERT_TRUE(loaded->control_ok) << loaded->last_error;
      EXPECT_NEAR(loaded->sim_time, 0.4, 1e-9);
      ASSERT_TRUE(client.StepAndWait(60)) << sim.Output();
      *out = client.states().begin()->second;
      EXPECT_GT(out->seq, original.seq);
    }

    // A checkpoint that cannot be read is refused; the sim carries on.
    auto bad = client.Control(sim_control_t::LOAD_CHECKPOINT, 0, 0,
                              dir + "/missing.ckpt");
    ASSERT_TRUE(bad);
    EXPECT_FALSE(bad->control_ok);
    EXPECT_NE(bad->last_error.find("missing.ckpt"), std::string::npos);
    EXPECT_EQ(bad->sim_time, loaded_twice.sim_time);
    EXPECT_EQ(sim.Stop(5.0), 0);
  }
  // Every continuation from the checkpoint is the same, bit for bit.
  {
    SCOPED_TRACE("second load vs first load");
    ExpectSameBody(loaded_once, loaded_twice);
  }
  // And the same as the run that was never interrupted (docs/sim.md).
  {
    SCOPED_TRACE("uninterrupted run vs first load");
    ExpectSameBody(original, loaded_once);
  }

  // A new process started from the checkpoint continues the same way.
  SimClient client(TestLcmUrl(port));
  ChildProcess sim({SimBinary(), "--load-checkpoint", checkpoint, "--lcm-url",
                    TestLcmUrl(port), "--rate", "100", "--clock", "lockstep",
                    "--controllers", "ctl", "--paused"},
                   dir + "/sim2.log");
  ChildProcess controller(
      {ControllerBinary(), "--lcm-url", TestLcmUrl(port), "--name", "ctl"});
  ASSERT_TRUE(client.WaitFor([&] { return client.status().has_value(); }, 10));
  EXPECT_NEAR(client.status()->sim_time, 0.4, 1e-9);
  ASSERT_TRUE(client.StepAndWait(60)) << sim.Output();
  SCOPED_TRACE("--load-checkpoint vs LOAD_CHECKPOINT");
  ExpectSameBody(client.states().begin()->second, loaded_once);
  EXPECT_EQ(sim.Stop(5.0), 0);
}

TEST(SimProcess, BadAndForeignMessagesAreCountedAndIgnored) {
  const std::string dir = TempDir("sim_bad");
  const std::string scenario = TestScenarioPath(dir);
  const Scenario model = ReadScenarioFile(scenario);
  const std::string robot = model.robots.at(0).name;
  const int joints = static_cast<int>(model.robots.at(0).modules.size());
  const int port = 7603;
  SimClient client(TestLcmUrl(port));
  ChildProcess sim(SimArgs(scenario, port, {"--clock", "fast", "--paused"}),
                   dir + "/sim.log");
  ASSERT_TRUE(client.WaitFor([&] { return client.status().has_value(); }, 10));
  lcm::LCM& lcm = client.lcm();
  const std::string channel = CommandChannel(kDefaultChannelPrefix, robot);

  int64_t seq = 0;
  auto command = [&](const std::string& name, std::vector<double> targets,
                     int64_t state_seq) {
    joint_command_t cmd{};
    cmd.seq = ++seq;
    cmd.robot = name;
    cmd.sender = "intruder";
    cmd.state_seq = state_seq;
    cmd.target = std::move(targets);
    cmd.num_joints = static_cast<int32_t>(cmd.target.size());
    return cmd;
  };
  const std::vector<double> zeros(joints, 0.3);
  const std::string garbage = "this is not an LCM message";
  for (int i = 0; i < 3; ++i) {
    lcm.publish(channel, garbage.data(), static_cast<unsigned>(garbage.size()));
  }
  lcm.publish(SimControlChannel(kDefaultChannelPrefix), garbage.data(),
              static_cast<unsigned>(garbage.size()));
  auto wrong_count = command(robot, std::vector<double>(joints - 1, 0.1), 0);
  lcm.publish(channel, &wrong_count);
  std::vector<double> nan = zeros, inf = zeros, huge = zeros;
  nan[2] = std::nan("");
  inf[4] = -HUGE_VAL;
  huge[0] = 4.0;  // beyond |pi|: not an angle
  for (auto* targets : {&nan, &inf, &huge}) {
    auto cmd = command(robot, *targets, 0);
    lcm.publish(channel, &cmd);
  }
  auto ghost = command("ghost", zeros, 0);
  lcm.publish(CommandChannel(kDefaultChannelPrefix, "ghost"), &ghost);
  auto mislabelled = command("ghost", zeros, 0);
  lcm.publish(channel, &mislabelled);
  auto future = command(robot, zeros, 999);  // answers a state never sent
  lcm.publish(channel, &future);

  auto counted = [&] {
    const auto& s = client.status();
    return s && s->messages_malformed == 4 && s->rejected_joint_count == 1 &&
           s->rejected_value == 3 && s->rejected_robot == 2 &&
           s->rejected_seq == 1;
  };
  ASSERT_TRUE(client.WaitFor(counted, 10.0))
      << "malformed " << client.status()->messages_malformed << " count "
      << client.status()->rejected_joint_count << " value "
      << client.status()->rejected_value << " robot "
      << client.status()->rejected_robot << " seq "
      << client.status()->rejected_seq;
  EXPECT_EQ(client.status()->commands_rejected, 7);
  EXPECT_EQ(client.status()->commands_applied, 0);

  // A flood of garbage and wrong commands: it survives and keeps counting.
  const auto before = *client.status();
  for (int i = 0; i < 3000; ++i) {
    if (i % 2 == 0) {
      lcm.publish(channel, garbage.data(),
                  static_cast<unsigned>(garbage.size()));
    } else {
      auto cmd = command(robot, nan, 0);
      lcm.publish(channel, &cmd);
    }
  }
  // Wait until the counters settle (the sim has drained its queues), so the
  // next request is not lost behind the flood.
  int64_t last_seq = client.status()->seq;
  int64_t last_total = -1;
  client.WaitFor(
      [&] {
        const auto& st = *client.status();
        if (st.seq == last_seq) return false;
        last_seq = st.seq;
        const int64_t total = st.messages_malformed + st.rejected_value;
        const bool settled = total == last_total;
        last_total = total;
        return settled;  // two heartbeats in a row with the same counts
      },
      20.0);
  auto after = client.Control(sim_control_t::PAUSE);
  ASSERT_TRUE(after) << "sim stopped answering after the flood";
  EXPECT_TRUE(sim.running());
  const int64_t flood_counted =
      (after->messages_malformed - before.messages_malformed) +
      (after->rejected_value - before.rejected_value);
  EXPECT_GT(flood_counted, 0);
  EXPECT_LE(flood_counted, 3000);
  EXPECT_EQ(after->commands_applied, 0);

  // None of that moved a joint: five periods match a run with no command.
  ASSERT_TRUE(client.StepAndWait(5)) << sim.Output();
  Physics reference(model);
  reference.Step(5 * client.status()->steps_per_period);
  const robot_state_t expected =
      ToRobotStateMessage(reference.ReadRobotState(0), 5);
  ExpectSameBody(client.states().at(robot), expected);

  // A good command still gets through, once; a stale one (an older
  // state) does not. The STEP after them is handled after them.
  const int64_t now_seq = client.status()->state_seq;
  auto good = command(robot, zeros, now_seq);
  lcm.publish(channel, &good);
  lcm.publish(channel, &good);
  auto stale = command(robot, zeros, now_seq - 1);
  lcm.publish(channel, &stale);
  ASSERT_TRUE(client.StepAndWait(1)) << client.Describe();
  EXPECT_EQ(client.status()->commands_applied, 1);
  EXPECT_EQ(client.status()->rejected_seq, 2) << client.Describe();
  EXPECT_EQ(sim.Stop(5.0), 0);
}

TEST(SimProcess, EveryRobotHasItsOwnChannels) {
  const std::string dir = TempDir("sim_two_robots");
  Scenario two;
  ChainOptions left;
  left.name = "left";
  left.modules = 5;
  ChainOptions right;
  right.name = "right";
  right.modules = 3;
  right.origin = Eigen::Vector3d(0, 1.0, 0);
  two.robots = {MakeChain(left), MakeChain(right)};
  const std::string scenario = dir + "/two.xml";
  WriteScenarioFile(two, scenario);
  const int port = 7610;
  SimClient client(TestLcmUrl(port));
  ChildProcess sim(SimArgs(scenario, port, {"--clock", "fast", "--paused"}),
                   dir + "/sim.log");
  ASSERT_TRUE(client.WaitFor([&] { return client.states().size() == 2; }, 10))
      << sim.Output();

  joint_command_t cmd{};
  cmd.seq = 1;
  cmd.robot = "right";
  cmd.sender = "test";
  cmd.state_seq = 0;
  cmd.target = {0.5, 0.5, 0.5};
  cmd.num_joints = 3;
  client.lcm().publish(CommandChannel(kDefaultChannelPrefix, "right"), &cmd);
  cmd.robot = "left";  // three targets for a five-joint robot
  client.lcm().publish(CommandChannel(kDefaultChannelPrefix, "left"), &cmd);
  ASSERT_TRUE(client.WaitFor(
      [&] { return client.status()->rejected_joint_count == 1; }, 5.0));

  ASSERT_TRUE(client.StepAndWait(20)) << sim.Output();
  const robot_state_t& l = client.states().at("left");
  const robot_state_t& r = client.states().at("right");
  EXPECT_EQ(l.seq, 20);
  EXPECT_EQ(r.seq, 20);
  EXPECT_EQ(l.num_joints, 5);
  EXPECT_EQ(r.num_joints, 3);
  for (const auto& j : r.joints) EXPECT_GT(j.angle, 0.2);
  for (const auto& j : l.joints) EXPECT_LT(std::abs(j.angle), 0.05);
  EXPECT_EQ(client.status()->commands_applied, 1);

  // A viewer that joins the paused sim gets both robots where they are.
  SimClient late(TestLcmUrl(port));
  ASSERT_TRUE(late.WaitFor([&] { return late.states().size() == 2; }, 10))
      << late.Describe();
  EXPECT_EQ(late.states().at("left").seq, 20);
  EXPECT_EQ(late.states().at("right").joints[0].angle, r.joints[0].angle);
  EXPECT_EQ(sim.Stop(5.0), 0);
}

TEST(SimProcess, SigtermStopsPromptlyAndWritesTheFinalCheckpoint) {
  const std::string dir = TempDir("sim_sigterm");
  const std::string scenario = TestScenarioPath(dir);
  const int port = 7604;
  SimClient client(TestLcmUrl(port));
  const std::string checkpoint = dir + "/final.ckpt";
  // Lockstep with no controller: the sim sits waiting, the hardest case.
  // Its lockstep wait lasts 30 s before it even warns: a stop within 15 s
  // was the signal's doing, not the wait's end, however busy the machine
  // (a 1 s bound failed under ctest -j6 on 2 cores).
  ChildProcess sim(
      SimArgs(scenario, port,
              {"--clock", "lockstep", "--controllers", "nobody",
               "--lockstep-timeout", "30", "--checkpoint-on-exit", checkpoint}),
      dir + "/sim.log");
  ASSERT_TRUE(client.WaitFor([&] { return client.status().has_value(); }, 10));
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(15.0), 0) << sim.Output();
  EXPECT_TRUE(std::filesystem::exists(checkpoint));
  EXPECT_NE(sim.Output().find("mrsim-sim: stopped (stop signal)"),
            std::string::npos)
      << sim.Output();
}

TEST(SimProcess, BadFlagsAndScenarioExitWithTwo) {
  const std::string dir = TempDir("sim_flags");
  const std::string scenario = TestScenarioPath(dir);
  ChildProcess no_controllers({SimBinary(), scenario, "--clock", "lockstep",
                               "--lcm-url", TestLcmUrl(7609)},
                              dir + "/a.log");
  EXPECT_EQ(no_controllers.Wait(10.0), 2);
  EXPECT_NE(no_controllers.Output().find("--controllers"), std::string::npos);
  ChildProcess bad_clock({SimBinary(), scenario, "--clock", "warp"},
                         dir + "/b.log");
  EXPECT_EQ(bad_clock.Wait(10.0), 2);
  EXPECT_NE(bad_clock.Output().find("warp"), std::string::npos);
  ChildProcess missing(
      {SimBinary(), dir + "/nope.xml", "--lcm-url", TestLcmUrl(7609)},
      dir + "/c.log");
  EXPECT_EQ(missing.Wait(10.0), 2);
  EXPECT_NE(missing.Output().find("nope.xml"), std::string::npos);
  ChildProcess version({SimBinary(), "--version"}, dir + "/d.log");
  EXPECT_EQ(version.Wait(10.0), 0);
  EXPECT_NE(version.Output().find("mrsim-sim " MRSIM_TEST_PROJECT_VERSION),
            std::string::npos)
      << version.Output();
  ChildProcess delay_without_lockstep(
      {SimBinary(), scenario, "--actuation-delay", "1"}, dir + "/e.log");
  EXPECT_EQ(delay_without_lockstep.Wait(10.0), 2);
  EXPECT_NE(delay_without_lockstep.Output().find("--actuation-delay"),
            std::string::npos);
}

}  // namespace
}  // namespace mrsim::testing

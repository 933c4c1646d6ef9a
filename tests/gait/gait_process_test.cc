// mrsim-gait as a real process over LCM on loopback: lockstep with
// mrsim-sim equals the in-process run, run-time gait commands, bad input.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <thread>

#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_runner.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/sim_process/sim_client.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::TempDir;
using testing::TestLcmUrl;

const std::string kGait = "gait_controller/process/mrsim-gait";
const std::string kSim = "sim_core/sim_process/mrsim-sim";

// An 11-module pitch-yaw snake named "snake" written to a scenario file.
std::string WriteSnake(const std::string& dir) {
  ChainOptions options;
  options.modules = 11;
  options.pattern = ChainPattern::kPitchYaw;
  Scenario scenario;
  scenario.robots.push_back(MakeChain(options));
  const std::string path = dir + "/snake.xml";
  WriteScenarioFile(scenario, path);
  return path;
}

struct Recorder {
  std::map<int64_t, robot_state_t> states;
  std::vector<joint_command_t> commands;
  void OnState(const lcm::ReceiveBuffer*, const std::string&,
               const robot_state_t* msg) {
    states[msg->seq] = *msg;
  }
  void OnCommand(const lcm::ReceiveBuffer*, const std::string&,
                 const joint_command_t* msg) {
    commands.push_back(*msg);
  }
};

// Handles LCM for `seconds` of wall time (or until done() says so).
void Pump(lcm::LCM& lcm, double seconds,
          const std::function<bool()>& done = nullptr) {
  const auto end =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    HandleFor(lcm, 10);
    if (done && done()) return;
  }
}

TEST(GaitProcess, LockstepOverLcmGivesTheInProcessTrajectory) {
  const std::string dir = TempDir("gait_process_lockstep");
  const std::string scenario = WriteSnake(dir);
  const std::string url = TestLcmUrl(7650);
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  Recorder rec;
  lcm::Subscription* sub =
      lcm.subscribe(StateChannel("MRSIM", "snake"), &Recorder::OnState, &rec);
  sub->setQueueCapacity(100000);

  ChildProcess gait(
      {BinaryPath(kGait), "--robot", "snake", "--scenario", scenario, "--gait",
       "turn-sharp", "--lcm-url", url, "--name", "g", "--exit-with-sim"},
      dir + "/gait.log");
  ChildProcess sim({BinaryPath(kSim), scenario, "--lcm-url", url, "--clock",
                    "lockstep", "--controllers", "g", "--duration", "3",
                    "--checkpoint-on-exit", dir + "/final.checkpoint"},
                   dir + "/sim.log");
  Pump(lcm, 60, [&] { return !sim.running(); });
  ASSERT_EQ(sim.Wait(5), 0) << sim.Output();
  // --exit-with-sim: the controller ends with the run, by itself.
  EXPECT_EQ(gait.Wait(20), 0) << gait.Output();
  EXPECT_NE(gait.Output().find("the simulator stopped"), std::string::npos)
      << gait.Output();
  EXPECT_NE(gait.Output().find("answered 301 states"), std::string::npos)
      << gait.Output();

  // The same gait in process, on the same scenario file.
  Physics physics(ReadScenarioFile(scenario));
  GaitController controller(JointAxes(physics, 0));
  controller.SetGait(*FindGaitPreset("turn-sharp"));
  std::vector<RobotState> expected = {physics.ReadRobotState(0)};
  RunGait(physics, 0, controller, 3.0, 0.01,
          [&](const Physics& p, const std::vector<double>&) {
            expected.push_back(p.ReadRobotState(0));
          });
  ASSERT_EQ(expected.size(), 301u);
  // The simulator's final physics state equals ours byte for byte...
  const auto final_state = LoadCheckpoint(dir + "/final.checkpoint");
  EXPECT_EQ(final_state->time(), physics.time());
  EXPECT_TRUE(final_state->SaveState() == physics.SaveState());
  // ...and so does every state message that arrived on the way (a busy
  // machine may drop a few datagrams on loopback; most must be there).
  EXPECT_GE(rec.states.size(), 150u);
  for (const auto& [seq, msg] : rec.states) {
    ASSERT_LT(seq, 301);
    const RobotState& want = expected[seq];
    EXPECT_EQ(msg.sim_time, want.time) << seq;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(msg.com[k], want.com[k]) << seq;
    ASSERT_EQ(msg.num_joints, static_cast<int>(want.joints.size()));
    for (int j = 0; j < msg.num_joints; ++j) {
      EXPECT_EQ(msg.joints[j].angle, want.joints[j].angle) << seq << " " << j;
    }
  }
  // The run did go somewhere (a sharp turn).
  EXPECT_GT(std::abs(expected.back().com.x() - expected.front().com.x()) +
                std::abs(expected.back().com.y() - expected.front().com.y()),
            0.01);
}

TEST(GaitProcess, GaitCommandsSteerAndBadOnesAreRejected) {
  const std::string dir = TempDir("gait_process_commands");
  const std::string scenario = WriteSnake(dir);
  const std::string url = TestLcmUrl(7651);
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  Recorder rec;
  lcm::Subscription* sub = lcm.subscribe(CommandChannel("MRSIM", "snake"),
                                         &Recorder::OnCommand, &rec);
  sub->setQueueCapacity(100000);
  ChildProcess gait({BinaryPath(kGait), "--robot", "snake", "--axes",
                     "pitch-yaw", "--lcm-url", url, "--name", "g"},
                    dir + "/gait.log");
  ChildProcess sim({BinaryPath(kSim), scenario, "--lcm-url", url, "--clock",
                    "realtime", "--speed", "2"},
                   dir + "/sim.log");
  Pump(lcm, 20, [&] { return !rec.commands.empty(); });
  ASSERT_FALSE(rec.commands.empty()) << gait.Output() << sim.Output();
  EXPECT_EQ(rec.commands.back().sender, "g");

  auto send = [&](gait_command_t c) {
    c.sender = "test";
    lcm.publish(GaitChannel("MRSIM", "snake"), &c);
  };
  gait_command_t turn{};
  turn.motion = "turn-left";
  turn.strength = 0.5;
  send(turn);
  Pump(lcm, 1.0);
  // Bad commands: each rejected whole.
  gait_command_t bad{};
  bad.gait = "moonwalk";
  send(bad);
  bad = {};
  bad.motion = "turn-right";
  bad.strength = std::nan("");
  send(bad);
  bad = {};
  bad.motion = "forward";
  bad.strength = 2;
  send(bad);
  bad = {};
  bad.has_parameters = true;
  const double params[7] = {1, 0, 2.5, 0, -4, 0, 0};  // negative period
  std::copy(params, params + 7, bad.parameters);
  bad.motion = "stop";  // must not apply: the command is rejected whole
  send(bad);
  bad = {};
  bad.robot = "other";
  bad.motion = "stop";
  send(bad);
  const char garbage[] = "not an lcm message";
  lcm.publish(GaitChannel("MRSIM", "snake"), garbage, sizeof(garbage));
  lcm.publish(StateChannel("MRSIM", "snake"), garbage, sizeof(garbage));
  rec.commands.clear();
  Pump(lcm, 1.5);
  ASSERT_GT(rec.commands.size(), 50u);
  // Still turning left as commanded: every yaw joint sits at the offset
  // -0.5 * 0.8 rad (forward gait: no yaw wave), the pitch joints wave.
  const joint_command_t& last = rec.commands.back();
  ASSERT_EQ(last.num_joints, 11);
  for (int j = 1; j < 11; j += 2) EXPECT_NEAR(last.target[j], -0.4, 1e-12);
  double pitch_range = 0;
  for (const auto& c : rec.commands) {
    pitch_range = std::max(pitch_range, std::abs(c.target[0]));
  }
  EXPECT_GT(pitch_range, 0.5);

  EXPECT_EQ(gait.Stop(5), 0);
  sim.Stop(5);
  const std::string out = gait.Output();
  EXPECT_NE(out.find("unknown gait 'moonwalk'"), std::string::npos) << out;
  EXPECT_NE(out.find("strength must be in [-1, 1], got nan"), std::string::npos)
      << out;
  EXPECT_NE(out.find("gait parameter T"), std::string::npos) << out;
  EXPECT_NE(out.find("for robot 'other'"), std::string::npos) << out;
  EXPECT_NE(out.find("gait commands applied 1, rejected 6"), std::string::npos)
      << out;
  EXPECT_NE(out.find("malformed messages 2"), std::string::npos) << out;
}

TEST(GaitProcess, LuaControllerExampleDrivesTheSimulator) {
  // examples/lua_controller: Lua (liblcm-lua) speaking the same messages,
  // in lockstep with mrsim-sim, moves the pitch snake toward its head.
  const std::string dir = TempDir("gait_process_lua");
  ChainOptions options;
  options.modules = 11;
  Scenario scenario;
  scenario.robots.push_back(MakeChain(options));
  const std::string path = dir + "/snake.xml";
  WriteScenarioFile(scenario, path);
  const std::string url = TestLcmUrl(7653);
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  Recorder rec;
  lcm.subscribe(StateChannel("MRSIM", "snake"), &Recorder::OnState, &rec)
      ->setQueueCapacity(100000);
  setenv("MRSIM_LUA_TYPES", (dir + "/lua_types").c_str(), 1);
  ChildProcess lua({testing::SourcePath("examples/lua_controller/run.sh"),
                    "--robot", "snake", "--lcm-url", url, "--duration", "4"},
                   dir + "/lua.log");
  unsetenv("MRSIM_LUA_TYPES");
  ChildProcess sim(
      {BinaryPath(kSim), path, "--lcm-url", url, "--clock", "lockstep",
       "--controllers", "lua", "--duration", "4", "--lockstep-timeout", "20"},
      dir + "/sim.log");
  Pump(lcm, 60, [&] { return !sim.running(); });
  ASSERT_EQ(sim.Wait(5), 0) << sim.Output() << lua.Output();
  // The last states may still wait in this process's socket when the
  // simulator is gone.
  Pump(lcm, 10, [&] { return rec.states.count(400) > 0; });
  EXPECT_EQ(lua.Wait(10), 0) << lua.Output();
  EXPECT_NE(lua.Output().find("answered 401 states"), std::string::npos)
      << lua.Output();
  ASSERT_TRUE(rec.states.count(0) && rec.states.count(400))
      << rec.states.size() << " states recorded";
  const double moved = rec.states[400].com[0] - rec.states[0].com[0];
  EXPECT_GT(moved, 0.03) << lua.Output();
  EXPECT_LT(std::abs(rec.states[400].com[1] - rec.states[0].com[1]), 0.01);
}

// Ctrl-C with no simulator sending states: liblcm-lua would wait for a
// message forever; the example still stops, and says how.
TEST(GaitProcess, LuaControllerExampleStopsOnCtrlCWithNoSimulator) {
  const std::string dir = TempDir("gait_process_lua_stop");
  setenv("MRSIM_LUA_TYPES", (dir + "/lua_types").c_str(), 1);
  ChildProcess lua({testing::SourcePath("examples/lua_controller/run.sh"),
                    "--robot", "snake", "--lcm-url", TestLcmUrl(7655)},
                   dir + "/lua.log");
  unsetenv("MRSIM_LUA_TYPES");
  ASSERT_TRUE(lua.WaitForOutput("caterpillar.lua: lua on", 30)) << lua.Output();
  lua.Signal(SIGINT);
  // Usually the interrupt finds it waiting for a message: terminated, 130.
  // One that lands while Lua code runs ends it cleanly, with its summary.
  const int code = lua.Wait(20);
  const std::string out = lua.Output();
  if (code == 0) {
    EXPECT_NE(out.find("answered 0 states"), std::string::npos) << out;
  } else {
    EXPECT_EQ(code, 130) << out;
    EXPECT_NE(out.find("stopped"), std::string::npos) << out;
  }
}

// A checkpoint taken while mrsim-gait drives the robot (mid-way through a
// turn it was told to make) resumes, with a fresh mrsim-sim and a fresh
// mrsim-gait --resume, to exactly the trajectory of the uninterrupted run.
TEST(GaitProcess, CheckpointWithTheGaitResumesTheSameTrajectory) {
  const std::string dir = TempDir("gait_process_checkpoint");
  const std::string scenario = WriteSnake(dir);
  const std::string checkpoint = dir + "/mid.ckpt";
  const std::string url = TestLcmUrl(7654);
  auto sim_args = [&](std::vector<std::string> first) {
    first.insert(first.begin(), BinaryPath(kSim));
    for (const char* a : {"--lcm-url", url.c_str(), "--clock", "lockstep",
                          "--controllers", "g", "--paused"}) {
      first.push_back(a);
    }
    return first;
  };
  auto gait_args = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = {
        BinaryPath(kGait), "--robot", "snake",  "--scenario", scenario,
        "--lcm-url",       url,       "--name", "g"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  robot_state_t uninterrupted, resumed;
  {
    testing::SimClient client(url);
    std::optional<gait_status_t> gait_status;
    struct Listener {
      std::optional<gait_status_t>* out;
      void On(const lcm::ReceiveBuffer*, const std::string&,
              const gait_status_t* msg) {
        *out = *msg;
      }
    } listener{&gait_status};
    client.lcm().subscribe(GaitStatusChannel("MRSIM", "snake"), &Listener::On,
                           &listener);
    ChildProcess sim(sim_args({scenario}), dir + "/sim1.log");
    ChildProcess gait(gait_args({}), dir + "/gait1.log");
    ASSERT_TRUE(
        client.WaitFor([&] { return client.status().has_value(); }, 20));
    ASSERT_TRUE(client.StepAndWait(100)) << sim.Output() << gait.Output();
    gait_command_t turn{};
    turn.seq = 1;
    turn.sender = "test";
    turn.motion = "turn-left";
    turn.strength = 0.7;
    client.lcm().publish(GaitChannel("MRSIM", "snake"), &turn);
    ASSERT_TRUE(client.WaitFor(
        [&] { return gait_status && gait_status->motion == "turn-left"; }, 20));
    ASSERT_TRUE(client.StepAndWait(50));
    auto saved =
        client.Control(sim_control_t::SAVE_CHECKPOINT, 0, 0, checkpoint);
    ASSERT_TRUE(saved && saved->control_ok);
    ASSERT_TRUE(client.StepAndWait(100));
    uninterrupted = client.states().at("snake");
    EXPECT_EQ(sim.Stop(5), 0);
    EXPECT_EQ(gait.Stop(5), 0);
    EXPECT_NE(gait.Output().find("saved the gait at sim time 1.5"),
              std::string::npos)
        << gait.Output();
  }
  {
    testing::SimClient client(url);
    ChildProcess sim(sim_args({"--load-checkpoint", checkpoint}),
                     dir + "/sim2.log");
    ChildProcess gait(gait_args({"--resume", checkpoint}), dir + "/gait2.log");
    ASSERT_TRUE(
        client.WaitFor([&] { return client.status().has_value(); }, 20));
    ASSERT_TRUE(client.StepAndWait(100)) << sim.Output() << gait.Output();
    resumed = client.states().at("snake");
    EXPECT_EQ(sim.Stop(5), 0);
    EXPECT_EQ(gait.Stop(5), 0);
  }
  EXPECT_NEAR(uninterrupted.sim_time, 2.5, 1e-9);
  EXPECT_EQ(resumed.sim_time, uninterrupted.sim_time);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(resumed.com[k], uninterrupted.com[k]);
  ASSERT_EQ(resumed.num_joints, uninterrupted.num_joints);
  for (int j = 0; j < resumed.num_joints; ++j) {
    EXPECT_EQ(resumed.joints[j].angle, uninterrupted.joints[j].angle) << j;
  }
}

TEST(GaitProcess, BadArgumentsExitWithTwo) {
  const std::string dir = TempDir("gait_process_args");
  auto run = [&](std::vector<std::string> args) {
    args.insert(args.begin(), BinaryPath(kGait));
    ChildProcess p(args, dir + "/out.log");
    const int code = p.Wait(20);
    return std::make_pair(code, p.Output());
  };
  auto [code, out] = run({"--robot", "snake", "--axes", "pitch", "--gait",
                          "moonwalk", "--lcm-url", TestLcmUrl(7652)});
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("unknown gait 'moonwalk'"), std::string::npos) << out;
  std::tie(code, out) = run({"--robot", "snake", "--scenario", "PY", "--axes",
                             "PY", "--lcm-url", TestLcmUrl(7652)});
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("not both"), std::string::npos) << out;
  std::tie(code, out) = run({"--robot", "snake", "--axes", "PXY"});
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("--axes"), std::string::npos) << out;
  std::tie(code, out) =
      run({"--robot", "snake", "--axes", "pitch", "--keyboard"});
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("not a terminal"), std::string::npos) << out;
  std::tie(code, out) = run({"--robot", "nobody", "--scenario", WriteSnake(dir),
                             "--lcm-url", TestLcmUrl(7652)});
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("no robot named 'nobody'"), std::string::npos) << out;
}

}  // namespace
}  // namespace mrsim

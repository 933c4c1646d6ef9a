// mrsim-ctl against a real mrsim-sim over loopback multicast.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <thread>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tools/ctl_client.h"
#include "tools/gait_command_request.h"
#include "tools/sim_control_request.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

TEST(SimControlRequest, ParsesEveryCommandAndNamesWhatIsWrong) {
  EXPECT_EQ(int{ParseSimControl({"pause"}).command}, int{sim_control_t::PAUSE});
  const sim_control_t step = ParseSimControl({"step", "25"});
  EXPECT_EQ(int{step.command}, int{sim_control_t::STEP});
  EXPECT_EQ(step.steps, 25);
  EXPECT_EQ(ParseSimControl({"save", "a.ckpt"}).path, "a.ckpt");
  EXPECT_EQ(int{ParseSimControl({"load", "a.ckpt"}).command},
            int{sim_control_t::LOAD_CHECKPOINT});
  EXPECT_DOUBLE_EQ(ParseSimControl({"speed", "0.5"}).speed, 0.5);
  const sim_control_t detach =
      ParseSimControl({"detach", "snake", "snake/lock3"});
  EXPECT_EQ(int{detach.command}, int{sim_control_t::DETACH});
  EXPECT_EQ(detach.robot, "snake");
  EXPECT_EQ(detach.lock, "snake/lock3");
  EXPECT_EQ(int{ParseSimControl({"attach", "a", "b"}).command},
            int{sim_control_t::ATTACH});
  EXPECT_THROW(ParseSimControl({"detach", "snake"}), std::invalid_argument);
  EXPECT_THROW(ParseSimControl({"step", "0"}), std::invalid_argument);
  EXPECT_THROW(ParseSimControl({"step", "1.5"}), std::invalid_argument);
  EXPECT_THROW(ParseSimControl({"speed", "-1"}), std::invalid_argument);
  EXPECT_THROW(ParseSimControl({"pause", "now"}), std::invalid_argument);
  try {
    ParseSimControl({"jump"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'jump'"), std::string::npos);
  }
}

// A typo names the command meant and lists every command, those mrsim-ctl
// handles itself (status, gait) too.
TEST(SimControlRequest, ATypoSuggestsTheNearestAndListsEveryCommand) {
  try {
    ParseSimControl({"pase"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown command 'pase' (did you mean 'pause'?)"),
              std::string::npos)
        << what;
    for (const char* command : {"resume", "quit", "status", "gait ROBOT"}) {
      EXPECT_NE(what.find(command), std::string::npos)
          << command << ": " << what;
    }
  }
  try {
    ParseSimControl({"stauts"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'status'?"),
              std::string::npos)
        << e.what();
  }
}

TEST(GaitRequest, ChecksMotionAndRangesBeforeSending) {
  const gait_command_t c = ParseGaitRequest(
      {"gait", "snake", "motion", "turn-left", "strength", "0.5"});
  EXPECT_EQ(c.robot, "snake");
  EXPECT_EQ(c.motion, "turn-left");
  EXPECT_EQ(c.strength, 0.5);
  EXPECT_EQ(ParseGaitRequest({"gait", "snake", "gait", "sidewind"}).gait,
            "sidewind");
  try {
    ParseGaitRequest({"gait", "snake", "motion", "trun-left"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown 'trun-left'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(ParseGaitRequest({"gait", "snake", "strength", "2"}),
               std::invalid_argument);
  EXPECT_THROW(ParseGaitRequest({"gait", "snake", "direction", "1"}),
               std::invalid_argument);
  EXPECT_THROW(ParseGaitRequest({"gait", "snake"}), std::invalid_argument);
}

double SimTime(const std::string& output) {
  std::smatch m;
  const std::regex re("sim time ([0-9.]+) s");
  if (!std::regex_search(output, m, re)) return -1;
  return std::stod(m[1]);
}

// A simulator left running in another terminal on the same URL and
// prefix: each simulator warns of the other, and `mrsim-ctl status` lists
// both. A resume reports the factor it runs at, not the paused 0.00.
TEST(MrsimCtl, TwoSimulatorsOnOneChannelAreBothNamed) {
  const std::string dir = TempDir("mrsim_ctl_two");
  const std::string url = TestLcmUrl(7885);
  const auto start = [&](const std::string& name) {
    return std::make_unique<ChildProcess>(
        std::vector<std::string>{BinaryPath("sim_core/sim_process/mrsim-sim"),
                                 SourcePath("scenarios/snake11.xml"),
                                 "--lcm-url", url, "--paused"},
        dir + "/" + name + ".log");
  };
  auto first = start("first");
  auto second = start("second");
  const std::string warning = "warning: another simulator (";
  EXPECT_TRUE(first->WaitForOutput(warning, 30)) << first->Output();
  EXPECT_TRUE(second->WaitForOutput(warning, 30)) << second->Output();
  auto ctl = [&](std::vector<std::string> words, const std::string& name) {
    std::vector<std::string> argv{BinaryPath("tools/mrsim-ctl"), "--lcm-url",
                                  url, "--timeout", "20"};
    argv.insert(argv.end(), words.begin(), words.end());
    ChildProcess p(argv, dir + "/" + name + ".log");
    const int code = p.Wait(60);
    return std::make_pair(code, p.Output());
  };
  const auto [code, out] = ctl({"status"}, "status");
  EXPECT_EQ(code, 0) << out;
  EXPECT_NE(out.find("2 simulators answer on MRSIM_SIM_STATUS"),
            std::string::npos)
      << out;
  for (const auto* sim : {first.get(), second.get()}) {
    EXPECT_NE(out.find(":" + std::to_string(sim->pid()) + ": sim time"),
              std::string::npos)
        << sim->pid() << "\n"
        << out;
  }
  second->Stop();
  const auto [resume_code, resume_out] = ctl({"resume"}, "resume");
  EXPECT_EQ(resume_code, 0) << resume_out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(resume_out, m,
                                std::regex("real-time factor ([0-9.]+)")))
      << resume_out;
  EXPECT_GT(std::stod(m[1]), 0.05) << resume_out;
}

TEST(MrsimCtl, StepsSavesAndQuitsARunningSimulator) {
  const std::string dir = TempDir("mrsim_ctl");
  const std::string url = TestLcmUrl(7880);
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"),
                    SourcePath("scenarios/snake11.xml"), "--lcm-url", url,
                    "--clock", "fast", "--paused"},
                   dir + "/sim.log");
  auto ctl = [&](std::vector<std::string> words, const std::string& name) {
    std::vector<std::string> argv{BinaryPath("tools/mrsim-ctl"), "--lcm-url",
                                  url, "--timeout", "20"};
    argv.insert(argv.end(), words.begin(), words.end());
    ChildProcess p(argv, dir + "/" + name + ".log");
    const int code = p.Wait(60);
    return std::make_pair(code, p.Output());
  };

  // Paused: ten control periods of 10 ms, then still paused; mrsim-ctl
  // says so once they ran.
  const auto [step_code, step_out] = ctl({"step", "10"}, "step");
  ASSERT_EQ(step_code, 0) << step_out << sim.Output();
  EXPECT_NE(step_out.find("step: done"), std::string::npos) << step_out;
  EXPECT_NEAR(SimTime(step_out), 0.1, 1e-9) << step_out;
  EXPECT_NE(step_out.find("paused"), std::string::npos) << step_out;
  const auto [status_code, status_out] = ctl({"status"}, "status");
  ASSERT_EQ(status_code, 0) << status_out;
  EXPECT_NEAR(SimTime(status_out), 0.1, 1e-9) << status_out;
  // Every mrsim-ctl run is its own sender: nothing counts as lost.
  EXPECT_NE(status_out.find("dropped 0"), std::string::npos) << status_out;
  EXPECT_NE(status_out.find("paused"), std::string::npos) << status_out;

  const std::string checkpoint = dir + "/mid.checkpoint";
  const auto [save_code, save_out] = ctl({"save", checkpoint}, "save");
  EXPECT_EQ(save_code, 0) << save_out;
  EXPECT_TRUE(std::filesystem::exists(checkpoint));
  // A relative path means the directory mrsim-ctl was run in, not the
  // simulator's, and the answer says where the file went.
  const std::string here = dir + "/elsewhere";
  std::filesystem::create_directories(here);
  ChildProcess relative(
      {"/bin/sh", "-c",
       "cd '" + here + "' && exec '" + BinaryPath("tools/mrsim-ctl") +
           "' save rel.checkpoint --lcm-url '" + url + "' --timeout 20"},
      dir + "/relative.log");
  EXPECT_EQ(relative.Wait(60), 0) << relative.Output();
  EXPECT_TRUE(std::filesystem::exists(here + "/rel.checkpoint"))
      << relative.Output();
  EXPECT_NE(relative.Output().find("save: done (" + here + "/rel.checkpoint)"),
            std::string::npos)
      << relative.Output();

  // Locks: detached and attached again on request; an unknown one refused.
  const auto [detach_code, detach_out] =
      ctl({"detach", "snake", "snake/lock3"}, "detach");
  EXPECT_EQ(detach_code, 0) << detach_out;
  EXPECT_NE(detach_out.find("detach: done"), std::string::npos) << detach_out;
  const auto [attach_code, attach_out] =
      ctl({"attach", "snake", "snake/lock3"}, "attach");
  EXPECT_EQ(attach_code, 0) << attach_out;
  const auto [nolock_code, nolock_out] =
      ctl({"detach", "snake", "snake/lock99"}, "nolock");
  EXPECT_EQ(nolock_code, 1) << nolock_out;
  EXPECT_NE(nolock_out.find("refused"), std::string::npos) << nolock_out;
  // The sim's whole error, first characters too (they were once read from
  // freed memory).
  EXPECT_NE(nolock_out.find("last error: DETACH: "), std::string::npos)
      << nolock_out;
  EXPECT_NE(nolock_out.find("snake/lock99"), std::string::npos) << nolock_out;
  // A later request that succeeds does not repeat that old error.
  const auto [again_code, again_out] =
      ctl({"attach", "snake", "snake/lock3"}, "again");
  EXPECT_EQ(again_code, 0) << again_out;
  EXPECT_EQ(again_out.find("last error"), std::string::npos) << again_out;

  const auto [bad_code, bad_out] = ctl({"warp", "9"}, "bad");
  EXPECT_EQ(bad_code, 2);
  EXPECT_NE(bad_out.find("unknown command 'warp'"), std::string::npos);
  const auto [extra_code, extra_out] = ctl({"status", "now"}, "extra");
  EXPECT_EQ(extra_code, 2);
  EXPECT_NE(extra_out.find("'status' takes no argument"), std::string::npos)
      << extra_out;

  const auto [quit_code, quit_out] = ctl({"quit"}, "quit");
  EXPECT_EQ(quit_code, 0) << quit_out;
  EXPECT_EQ(sim.Wait(30), 0) << sim.Output();
}

TEST(MrsimCtl, NoSimulatorIsReportedNotAwaitedForever) {
  const std::string dir = TempDir("mrsim_ctl_alone");
  // Options after the command count too, as with every other program.
  ChildProcess p({BinaryPath("tools/mrsim-ctl"), "--lcm-url", TestLcmUrl(7881),
                  "pause", "--timeout", "0.5", "--prefix", "OTHER"},
                 dir + "/ctl.log");
  EXPECT_EQ(p.Wait(30), 1);
  EXPECT_NE(p.Output().find("no answer from a simulator on OTHER_SIM_STATUS "
                            "within 0.5 s"),
            std::string::npos)
      << p.Output();
}

// Something that is not a simulator talking on the status channel (another
// program, another mrsim version) is named when nothing answers, and does
// not crash mrsim-ctl.
TEST(MrsimCtl, UnreadableMessagesOnTheStatusChannelAreNamed) {
  const std::string url = TestLcmUrl(7884);
  lcm::LCM talker(url);
  ASSERT_TRUE(talker.good());
  std::atomic<bool> done{false};
  std::thread noise([&] {
    // Bytes that are not a sim_status_t, from a stand-in source with a
    // steady rate until mrsim-ctl has given up.
    const std::vector<std::uint8_t> junk(64, 0xff);
    testing::RepeatUntil(
        [&] {
          talker.publish(SimStatusChannel("MRSIM"), junk.data(),
                         static_cast<unsigned>(junk.size()));
        },
        [&] { return done.load(); }, 0.02, 60);
  });
  SignedLcm lcm(url);
  CtlOptions options;
  options.timeout = 1.0;
  options.sender = "ctl-test";
  std::ostringstream out, err;
  const int code = RunCtl(lcm, {"pause"}, options, out, err);
  done = true;
  noise.join();
  EXPECT_EQ(code, 1);
  EXPECT_NE(err.str().find("no answer"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("could not be read"), std::string::npos)
      << err.str();
}

// A step the simulator took but could not finish (lockstep with its
// controller missing) is not reported as done.
TEST(MrsimCtl, AStepThatCannotFinishFails) {
  const std::string dir = TempDir("mrsim_ctl_stuck");
  const std::string url = TestLcmUrl(7883);
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"),
                    SourcePath("scenarios/snake11.xml"), "--lcm-url", url,
                    "--clock", "lockstep", "--controllers", "nobody"},
                   dir + "/sim.log");
  ChildProcess p({BinaryPath("tools/mrsim-ctl"), "--lcm-url", url, "--timeout",
                  "5", "step", "5"},
                 dir + "/ctl.log");
  EXPECT_EQ(p.Wait(60), 1) << p.Output();
  EXPECT_NE(p.Output().find("5 periods not done"), std::string::npos)
      << p.Output();
}

// A robot that runs but whose controller takes no gait commands (a Lua
// script without on_gait_command, a program of one's own: it never sends a
// gait status) is named as such
// soon after its states are heard, not waited for until the timeout.
TEST(MrsimCtl, SteeringARobotNothingSteersFailsAtOnceAndSaysWhy) {
  const std::string url = TestLcmUrl(7889);
  lcm::LCM talker(url);
  ASSERT_TRUE(talker.good());
  std::atomic<bool> done{false};
  std::thread states([&] {
    // The worm's states, as mrsim-sim sends them, and nothing on its gait
    // status channel.
    robot_state_t state{};
    state.robot = "worm";
    testing::RepeatUntil(
        [&] {
          ++state.seq;
          state.sim_time += 0.02;
          talker.publish(StateChannel("MRSIM", "worm"), &state);
        },
        [&] { return done.load(); }, 0.02, 60);
  });
  SignedLcm lcm(url);
  CtlOptions options;
  options.timeout = 30;  // the other message would say "within 30.0 s"
  options.sender = "ctl-test";
  std::ostringstream out, err;
  const int code =
      RunCtl(lcm, {"gait", "worm", "motion", "forward"}, options, out, err);
  done = true;
  states.join();
  EXPECT_EQ(code, 1);
  EXPECT_NE(err.str().find("nothing steers robot 'worm': it runs"),
            std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find("on_gait_command"), std::string::npos) << err.str();
}

// A Lua script that defines on_gait_command takes steering as mrsim-gait
// does: mrsim-ctl hears its gait status, sends, and reports the script's
// verdict, its reason included when it refuses.
TEST(MrsimCtl, SteersALuaScriptThatTakesGaitCommands) {
  const std::string dir = TempDir("mrsim_ctl_lua");
  const std::string url = TestLcmUrl(7888);
  const std::string script = dir + "/steered.lua";
  {
    std::ofstream f(script);
    f << "local speed = 1\n"
         "function on_gait_command(cmd)\n"
         "  if cmd.motion == 'stop' then speed = 0\n"
         "  elseif cmd.motion then return false, 'only stop here' end\n"
         "end\n"
         "function step(t, state)\n"
         "  local out = {}\n"
         "  for i = 1, state.n do out[i] = speed * math.sin(t - i) end\n"
         "  return out\n"
         "end\n";
  }
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"),
                    SourcePath("scenarios/snake11.xml"), "--lcm-url", url},
                   dir + "/sim.log");
  ChildProcess lua({BinaryPath("lua_controller/process/mrsim-lua"), "--robot",
                    "snake", "--scenario", SourcePath("scenarios/snake11.xml"),
                    "--script", script, "--lcm-url", url},
                   dir + "/lua.log");
  auto ctl = [&](std::vector<std::string> words, const std::string& name) {
    std::vector<std::string> argv{BinaryPath("tools/mrsim-ctl"), "--lcm-url",
                                  url, "--timeout", "20"};
    argv.insert(argv.end(), words.begin(), words.end());
    ChildProcess p(argv, dir + "/" + name + ".log");
    const int code = p.Wait(60);
    return std::make_pair(code, p.Output());
  };
  auto [code, out] = ctl({"gait", "snake", "motion", "stop"}, "stop");
  EXPECT_EQ(code, 0) << out << lua.Output();
  EXPECT_NE(out.find("gait: done"), std::string::npos) << out;
  std::tie(code, out) = ctl({"gait", "snake", "motion", "roll"}, "roll");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("refused by the Lua script: only stop here"),
            std::string::npos)
      << out;
  EXPECT_EQ(lua.Stop(5), 0) << lua.Output();
  EXPECT_EQ(sim.Stop(5), 0);
}

// mrsim-ctl gait waits for mrsim-gait's heartbeat, sends once and reports
// what mrsim-gait made of it; typos fail with a message and a non-zero exit.
TEST(MrsimCtl, GaitCommandsAreAcknowledgedAndTyposFail) {
  const std::string dir = TempDir("mrsim_ctl_gait");
  const std::string url = TestLcmUrl(7882);
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"),
                    SourcePath("scenarios/snake11.xml"), "--lcm-url", url,
                    "--clock", "lockstep", "--controllers", "gait-snake"},
                   dir + "/sim.log");
  // What mrsim-gait says it runs.
  lcm::LCM lcm(url);
  std::optional<gait_status_t> status;
  struct Listener {
    std::optional<gait_status_t>* out;
    void On(const lcm::ReceiveBuffer*, const std::string&,
            const gait_status_t* msg) {
      *out = *msg;
    }
  } listener{&status};
  lcm.subscribe(GaitStatusChannel("MRSIM", "snake"), &Listener::On, &listener);
  ChildProcess gait(
      {BinaryPath("gait_controller/process/mrsim-gait"), "--robot", "snake",
       "--scenario", SourcePath("scenarios/snake11.xml"), "--lcm-url", url},
      dir + "/gait.log");
  auto ctl = [&](std::vector<std::string> words, const std::string& name) {
    std::vector<std::string> argv{BinaryPath("tools/mrsim-ctl"), "--lcm-url",
                                  url, "--timeout", "20"};
    argv.insert(argv.end(), words.begin(), words.end());
    ChildProcess p(argv, dir + "/" + name + ".log");
    const int code = p.Wait(60);
    return std::make_pair(code, p.Output());
  };
  // Sent at once after mrsim-gait starts: not lost; applied, or queued
  // until the first state and applied then.
  auto [code, out] = ctl({"gait", "snake", "gait", "forward-strong"}, "strong");
  EXPECT_EQ(code, 0) << out << gait.Output();
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!(status && status->running && status->gait == "forward-strong") &&
         std::chrono::steady_clock::now() < end) {
    HandleFor(lcm, 20);
  }
  ASSERT_TRUE(status && status->gait == "forward-strong")
      << out << gait.Output();
  EXPECT_EQ(status->commands_applied, 1);

  std::tie(code, out) = ctl({"gait", "snake", "motion", "trun-left"}, "typo");
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("unknown 'trun-left'"), std::string::npos) << out;

  std::tie(code, out) = ctl({"gait", "snake", "gait", "moonwalk"}, "moon");
  EXPECT_EQ(code, 1);
  EXPECT_NE(out.find("refused by mrsim-gait"), std::string::npos) << out;
  EXPECT_NE(out.find("moonwalk"), std::string::npos) << out;

  ChildProcess nobody({BinaryPath("tools/mrsim-ctl"), "--lcm-url", url,
                       "--timeout", "1.5", "gait", "snaek", "motion", "stop"},
                      dir + "/nobody.log");
  EXPECT_EQ(nobody.Wait(30), 1);
  EXPECT_NE(nobody.Output().find("no mrsim-gait for robot 'snaek'"),
            std::string::npos)
      << nobody.Output();

  ChildProcess version({BinaryPath("tools/mrsim-ctl"), "--version"},
                       dir + "/version.log");
  EXPECT_EQ(version.Wait(30), 0);
  EXPECT_NE(version.Output().find("mrsim-ctl "), std::string::npos);
  EXPECT_EQ(gait.Stop(5), 0);
  EXPECT_EQ(sim.Stop(5), 0);
}

}  // namespace
}  // namespace mrsim

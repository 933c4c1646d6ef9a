// mrsim-lua as a real process over LCM on loopback: a template script in
// lockstep with mrsim-sim moves the robot; a broken script exits 2 naming
// its line.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/robot_state_t.hpp"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

const std::string kLua = "lua_controller/process/mrsim-lua";
const std::string kSim = "sim_core/sim_process/mrsim-sim";

struct Recorder {
  std::map<int64_t, robot_state_t> states;
  void OnState(const lcm::ReceiveBuffer*, const std::string&,
               const robot_state_t* msg) {
    states[msg->seq] = *msg;
  }
};

void Pump(lcm::LCM& lcm, double seconds, const std::function<bool()>& done) {
  const auto end =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end && !done()) HandleFor(lcm, 10);
}

TEST(LuaProcess, SerpenoidTemplateDrivesTheSimulatorInLockstep) {
  const std::string dir = TempDir("lua_process_serpenoid");
  ChainOptions options;
  options.modules = 11;
  Scenario scenario;
  scenario.robots.push_back(MakeChain(options));
  const std::string path = dir + "/snake.xml";
  WriteScenarioFile(scenario, path);
  const std::string url = TestLcmUrl(7943);
  // Every one of the 301 states must reach this recorder: in lockstep the
  // simulator paces itself on the controller, not on the test, and with
  // six tests on two cores this process can be off the CPU while a few
  // hundred kilobytes of states arrive (the default 208 KiB socket buffer
  // kept 65 of 301). LCM asks the kernel for more (up to rmem_max).
  lcm::LCM lcm(url + "&recv_buf_size=4194304");
  ASSERT_TRUE(lcm.good());
  Recorder rec;
  lcm.subscribe(StateChannel("MRSIM", "snake"), &Recorder::OnState, &rec)
      ->setQueueCapacity(100000);
  ChildProcess lua({BinaryPath(kLua), "--robot", "snake", "--script",
                    SourcePath("lua_controller/templates/serpenoid.lua"),
                    "--scenario", path, "--lcm-url", url, "--exit-with-sim"},
                   dir + "/lua.log");
  ChildProcess sim({BinaryPath(kSim), path, "--lcm-url", url, "--clock",
                    "lockstep", "--controllers", "lua-snake", "--duration", "3",
                    "--lockstep-timeout", "20"},
                   dir + "/sim.log");
  Pump(lcm, 60, [&] { return !sim.running(); });
  ASSERT_EQ(sim.Wait(5), 0) << sim.Output() << lua.Output();
  Pump(lcm, 10, [&] { return rec.states.count(300) > 0; });
  EXPECT_EQ(lua.Wait(20), 0) << lua.Output();
  EXPECT_NE(lua.Output().find("answered 301 states"), std::string::npos)
      << lua.Output();
  ASSERT_TRUE(rec.states.count(0) && rec.states.count(300))
      << rec.states.size() << " states recorded";
  // The joints followed the wave and the robot went somewhere.
  double swing = 0;
  for (const joint_state_t& j : rec.states[300].joints) {
    swing = std::max(swing, std::abs(j.angle));
  }
  EXPECT_GT(swing, 0.1);
  const double moved =
      std::hypot(rec.states[300].com[0] - rec.states[0].com[0],
                 rec.states[300].com[1] - rec.states[0].com[1]);
  EXPECT_GT(moved, 0.01) << lua.Output();
}

TEST(LuaProcess, BrokenScriptExitsTwoNamingItsLine) {
  const std::string dir = TempDir("lua_process_broken");
  const std::string script = dir + "/broken.lua";
  {
    FILE* f = std::fopen(script.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("function step(t, state)\n  return {t +}\nend\n", f);
    std::fclose(f);
  }
  ChildProcess check(
      {BinaryPath(kLua), "--robot", "snake", "--script", script, "--check"},
      dir + "/check.log");
  EXPECT_EQ(check.Wait(20), 2);
  EXPECT_NE(check.Output().find("broken.lua:2:"), std::string::npos)
      << check.Output();
  ChildProcess missing(
      {BinaryPath(kLua), "--robot", "snake", "--script", dir + "/none.lua"},
      dir + "/missing.log");
  EXPECT_EQ(missing.Wait(20), 2);
  EXPECT_NE(missing.Output().find("none.lua"), std::string::npos);
}

}  // namespace
}  // namespace mrsim

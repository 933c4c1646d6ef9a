// Signed messages with real processes: a simulator started with a key
// obeys only senders holding it. LCM ports 7930-7934.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <string>
#include <utility>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "mrsim/sim_control_t.hpp"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

std::pair<int, std::string> RunProgram(const std::vector<std::string>& argv,
                                       const std::string& log) {
  ChildProcess p(argv, log);
  const int code = p.Wait(60);
  return {code, p.Output()};
}

TEST(SignedMessages, KeygenWritesAPrivateKeyOnceAndEveryProgramChecksIt) {
  const std::string dir = TempDir("signed_keygen");
  const std::string key = dir + "/farm.key";
  const auto [code, out] = RunProgram(
      {BinaryPath("launcher/mrsim"), "keygen", key}, dir + "/keygen.log");
  ASSERT_EQ(code, 0) << out;
  struct stat st {};
  ASSERT_EQ(stat(key.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  const auto [again, again_out] = RunProgram(
      {BinaryPath("launcher/mrsim"), "keygen", key}, dir + "/again.log");
  EXPECT_EQ(again, 2) << again_out;

  chmod(key.c_str(), 0644);
  const auto [open_code, open_out] =
      RunProgram({BinaryPath("tools/mrsim-ctl"), "--key-file", key, "status"},
                 dir + "/open.log");
  EXPECT_EQ(open_code, 2) << open_out;
  EXPECT_NE(open_out.find(key), std::string::npos) << open_out;
  EXPECT_NE(open_out.find("chmod 600"), std::string::npos) << open_out;
}

TEST(SignedMessages, WithoutTheKeyNobodySteersPausesOrStopsTheSimulator) {
  const std::string dir = TempDir("signed_sim");
  const std::string url = TestLcmUrl(7930);
  const std::string key = dir + "/farm.key";
  const std::string other = dir + "/other.key";
  ASSERT_EQ(RunProgram({BinaryPath("launcher/mrsim"), "keygen", key}, "").first,
            0);
  ASSERT_EQ(
      RunProgram({BinaryPath("launcher/mrsim"), "keygen", other}, "").first, 0);
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"),
                    SourcePath("scenarios/snake11.xml"), "--lcm-url", url,
                    "--key-file", key},
                   dir + "/sim.log");
  // A gait controller without the key reads the states (signing does not
  // hide them) but its commands are dropped.
  ChildProcess gait(
      {BinaryPath("gait_controller/process/mrsim-gait"), "--robot", "snake",
       "--scenario", SourcePath("scenarios/snake11.xml"), "--lcm-url", url,
       "--name", "intruder"},
      dir + "/gait.log");
  ASSERT_TRUE(sim.WaitForOutput(
      "dropped an unsigned message on MRSIM_COMMAND_snake", 30))
      << sim.Output() << gait.Output();

  const auto ctl = [&](std::vector<std::string> words,
                       const std::string& key_file, const std::string& name) {
    std::vector<std::string> argv{BinaryPath("tools/mrsim-ctl"), "--lcm-url",
                                  url, "--timeout", "2"};
    if (!key_file.empty()) {
      argv.push_back("--key-file");
      argv.push_back(key_file);
    }
    argv.insert(argv.end(), words.begin(), words.end());
    return RunProgram(argv, dir + "/" + name + ".log");
  };
  // No key: the requests are sent (the status is readable) and never
  // acknowledged.
  EXPECT_NE(ctl({"pause"}, "", "pause").first, 0);
  EXPECT_NE(ctl({"quit"}, "", "quit").first, 0);
  EXPECT_TRUE(
      sim.WaitForOutput("dropped an unsigned message on MRSIM_SIM_CONTROL", 30))
      << sim.Output();
  // Another key: mrsim-ctl takes the simulator's status for forged and
  // says so; a QUIT signed with that key is dropped as forged.
  const auto [forged_code, forged_out] = ctl({"quit"}, other, "forged");
  EXPECT_NE(forged_code, 0);
  EXPECT_NE(forged_out.find("dropped a forged message on MRSIM_SIM_STATUS"),
            std::string::npos)
      << forged_out;
  SignedLcm forger(url, LoadAuthConfig(other, false));
  sim_control_t quit{};
  quit.sender = "forger";
  quit.command = sim_control_t::QUIT;
  ASSERT_TRUE(testing::RepeatUntil(
      [&] {
        ++quit.seq;
        forger.publish(SimControlChannel("MRSIM"), &quit);
      },
      [&] {
        return sim.Output().find(
                   "dropped a forged message on MRSIM_SIM_CONTROL") !=
               std::string::npos;
      },
      0.05, 30))
      << sim.Output();
  EXPECT_TRUE(sim.running()) << sim.Output();

  const auto [status_code, status] = ctl({"status"}, key, "status");
  ASSERT_EQ(status_code, 0) << status;
  EXPECT_NE(status.find("running"), std::string::npos) << status;
  EXPECT_NE(status.find("commands applied 0,"), std::string::npos) << status;
  gait.Stop();

  const auto [quit_code, quit_out] = ctl({"quit"}, key, "signed_quit");
  EXPECT_EQ(quit_code, 0) << quit_out;
  EXPECT_EQ(sim.Wait(30), 0) << sim.Output();
}

}  // namespace
}  // namespace mrsim

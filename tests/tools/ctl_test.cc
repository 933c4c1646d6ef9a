// mrsim-ctl against a real mrsim-sim over loopback multicast.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "tests/common/child_process.h"
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

double SimTime(const std::string& output) {
  std::smatch m;
  const std::regex re("sim time ([0-9.]+) s");
  if (!std::regex_search(output, m, re)) return -1;
  return std::stod(m[1]);
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

  // Paused: ten control periods of 10 ms, then still paused.
  const auto [step_code, step_out] = ctl({"step", "10"}, "step");
  ASSERT_EQ(step_code, 0) << step_out << sim.Output();
  // The answer comes when the request is taken; the periods run after it.
  std::string status_out;
  for (int i = 0; i < 20; ++i) {
    const auto [status_code, out] = ctl({"status"}, "status");
    ASSERT_EQ(status_code, 0) << out;
    status_out = out;
    if (status_out.find("paused") != std::string::npos) break;
  }
  EXPECT_NEAR(SimTime(status_out), 0.1, 1e-9) << status_out;
  EXPECT_NE(status_out.find("paused"), std::string::npos) << status_out;

  const std::string checkpoint = dir + "/mid.checkpoint";
  const auto [save_code, save_out] = ctl({"save", checkpoint}, "save");
  EXPECT_EQ(save_code, 0) << save_out;
  EXPECT_TRUE(std::filesystem::exists(checkpoint));

  const auto [bad_code, bad_out] = ctl({"warp", "9"}, "bad");
  EXPECT_EQ(bad_code, 2);
  EXPECT_NE(bad_out.find("unknown command 'warp'"), std::string::npos);

  const auto [quit_code, quit_out] = ctl({"quit"}, "quit");
  EXPECT_EQ(quit_code, 0) << quit_out;
  EXPECT_EQ(sim.Wait(30), 0) << sim.Output();
}

TEST(MrsimCtl, NoSimulatorIsReportedNotAwaitedForever) {
  const std::string dir = TempDir("mrsim_ctl_alone");
  ChildProcess p({BinaryPath("tools/mrsim-ctl"), "--lcm-url", TestLcmUrl(7881),
                  "--timeout", "0.5", "pause"},
                 dir + "/ctl.log");
  EXPECT_EQ(p.Wait(30), 1);
  EXPECT_NE(p.Output().find("no answer"), std::string::npos) << p.Output();
}

}  // namespace
}  // namespace mrsim

// The programs with an exploding scenario: a clear error, nothing from
// MuJoCo on stdout, no MUJOCO_LOG.TXT, and the process decides what
// happens next (MuJoCo does not end it).
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/mujoco_embedding/exploding_scenario.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;
using testing::BinaryPath;
using testing::ChildProcess;
using testing::ReadFileText;
using testing::TestLcmUrl;
using testing::WaitForFileText;

// Runs in a fresh directory, the processes' working directory.
class ExplodingProcess : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::TempDir(
        std::string("exploding_") +
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    old_ = fs::current_path();
    fs::current_path(dir_);
    WriteScenarioFile(testing::ExplodingScenario(), dir_ + "/ex.xml");
  }
  void TearDown() override {
    EXPECT_FALSE(fs::exists(fs::path(dir_) / "MUJOCO_LOG.TXT"));
    fs::current_path(old_);
  }
  std::string dir_;
  fs::path old_;
};

// MuJoCo's default warning text, which must never reach stdout.
constexpr char kMujocoText[] = "Nan, Inf or huge value";

TEST_F(ExplodingProcess, SimulatorNamesTheErrorAndKeepsStdoutClean) {
  // stdout and stderr apart: stdout is for the run's summary only.
  ChildProcess sim(
      {"/bin/sh", "-c",
       "exec \"$0\" ex.xml --clock fast --no-state --lcm-url \"$1\" "
       "2>err.txt",
       BinaryPath("sim_core/sim_process/mrsim-sim"), TestLcmUrl(7900)},
      dir_ + "/out.txt");
  ASSERT_TRUE(WaitForFileText(dir_ + "/err.txt", "physics unstable", 60))
      << ReadFileText(dir_ + "/err.txt");
  const std::string err = ReadFileText(dir_ + "/err.txt");
  EXPECT_NE(err.find("BADQACC"), std::string::npos) << err;
  // Interactive (no --duration): paused on the error, so a user may RESET;
  // a stop request still ends it cleanly.
  EXPECT_NE(err.find("paused"), std::string::npos) << err;
  sim.Signal(SIGINT);
  EXPECT_EQ(sim.Wait(30), 0);
  const std::string out = ReadFileText(dir_ + "/out.txt");
  EXPECT_EQ(out.find(kMujocoText), std::string::npos) << out;
  EXPECT_EQ(out.find("WARNING"), std::string::npos) << out;
}

TEST_F(ExplodingProcess, BatchSimulatorEndsWithAFailureExit) {
  ChildProcess sim(
      {"/bin/sh", "-c",
       "exec \"$0\" ex.xml --clock fast --duration 60 --no-state "
       "--checkpoint-on-exit end.checkpoint --lcm-url \"$1\" 2>err.txt",
       BinaryPath("sim_core/sim_process/mrsim-sim"), TestLcmUrl(7902)},
      dir_ + "/out.txt");
  // Nobody can RESET a batch run: it ends by itself, non-zero, and keeps
  // no checkpoint of the failed state.
  EXPECT_EQ(sim.Wait(60), 1) << ReadFileText(dir_ + "/err.txt");
  const std::string err = ReadFileText(dir_ + "/err.txt");
  EXPECT_NE(err.find("physics unstable"), std::string::npos) << err;
  EXPECT_NE(err.find("run ended"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/end.checkpoint"));
  EXPECT_EQ(ReadFileText(dir_ + "/out.txt").find(kMujocoText),
            std::string::npos);
}

TEST_F(ExplodingProcess, WorkerReportsFailedEpisodesAndLivesOn) {
  {
    std::ofstream genome(dir_ + "/g.xml");
    genome << "<genome robot=\"snake\"><gene name=\"A_pitch\" lower=\"0\" "
              "upper=\"1.5\" start=\"1\"/></genome>\n";
  }
  const std::string url = TestLcmUrl(7901);
  ChildProcess worker({BinaryPath("optimizer/process/mrsim-worker"),
                       "--lcm-url", url, "--id", "w1"},
                      dir_ + "/worker.log");
  ChildProcess master(
      {BinaryPath("optimizer/process/mrsim-opt"), "ex.xml", "--genome", "g.xml",
       "--generations", "1", "--population", "4", "--seed", "3", "--episode",
       "20", "--out", dir_ + "/run", "--farm", "--lcm-url", url},
      dir_ + "/master.log");
  ASSERT_EQ(master.Wait(120), 0) << master.Output();
  EXPECT_TRUE(worker.running()) << worker.Output();
  const std::string evaluations = ReadFileText(dir_ + "/run/evaluations.csv");
  EXPECT_NE(evaluations.find("-1000000"), std::string::npos) << evaluations;
  EXPECT_EQ(worker.Output().find(kMujocoText), std::string::npos)
      << worker.Output();
  EXPECT_EQ(master.Output().find(kMujocoText), std::string::npos)
      << master.Output();
  EXPECT_EQ(worker.Stop(), 0) << worker.Output();
}

}  // namespace
}  // namespace mrsim

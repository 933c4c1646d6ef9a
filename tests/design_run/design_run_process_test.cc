// `mrsim run FILE` as a user runs it: the saved controller drives the
// robot and the summary line ends the run; an overlapping design is
// refused (exit 2) naming the ball, unless --allow-overlap. mrsim-sim
// refuses it the same way.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "tests/common/child_process.h"
#include "tests/design_run/overlapping_design.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using ::testing::HasSubstr;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

TEST(MrsimRun, RunsTheSavedLuaControllerAndEndsWithTheSummary) {
  const std::string dir = TempDir("mrsim_run_lua");
  ChildProcess run(
      {BinaryPath("launcher/mrsim"), "run",
       SourcePath("scenarios/lua_serpenoid.xml"), "--duration", "5",
       "--without", "view", "--out", dir, "--lcm-url", TestLcmUrl(7812)},
      dir + "/output.txt");
  ASSERT_TRUE(run.WaitForOutput("5.0 s: snake moved ", 180)) << run.Output();
  EXPECT_EQ(run.Wait(30), 0) << run.Output();
  // The Lua node ran (its start line, prefixed with its name).
  EXPECT_THAT(run.Output(), HasSubstr("mrsim-lua: robot snake"));
}

TEST(MrsimRun, AnOverlappingDesignExits2NamingTheBall) {
  const std::string dir = TempDir("mrsim_run_overlap");
  const std::string file = testing::WriteOverlappingDesign(dir);
  ChildProcess run({BinaryPath("launcher/mrsim"), "run", file, "--duration",
                    "1", "--without", "view", "--out", dir + "/out",
                    "--lcm-url", TestLcmUrl(7814)},
                   dir + "/output.txt");
  EXPECT_EQ(run.Wait(60), 2) << run.Output();
  EXPECT_THAT(run.Output(), HasSubstr("scene object 'ball' by "));
  EXPECT_THAT(run.Output(), HasSubstr("--allow-overlap"));
}

TEST(MrsimRun, AllowOverlapRunsAnOverlappingDesign) {
  const std::string dir = TempDir("mrsim_run_allow_overlap");
  const std::string file = testing::WriteOverlappingDesign(dir);
  ChildProcess run({BinaryPath("launcher/mrsim"), "run", file, "--duration",
                    "1", "--without", "view", "--out", dir + "/out",
                    "--lcm-url", TestLcmUrl(7815), "--allow-overlap"},
                   dir + "/output.txt");
  ASSERT_TRUE(run.WaitForOutput("case_study moved ", 120)) << run.Output();
  EXPECT_EQ(run.Wait(30), 0) << run.Output();
}

TEST(MrsimSim, RefusesAnOverlappingDesignUnlessAllowed) {
  const std::string dir = TempDir("mrsim_sim_overlap");
  const std::string file = testing::WriteOverlappingDesign(dir);
  const std::string sim = BinaryPath("sim_core/sim_process/mrsim-sim");
  ChildProcess refused({sim, file, "--duration", "0.2", "--clock", "fast",
                        "--lcm-url", TestLcmUrl(7816)},
                       dir + "/refused.txt");
  EXPECT_EQ(refused.Wait(60), 2) << refused.Output();
  EXPECT_THAT(refused.Output(),
              ::testing::ContainsRegex(
                  "robot 'case_study' module 0 (front|back) frame"));
  EXPECT_THAT(refused.Output(), HasSubstr("scene object 'ball' by "));
  ChildProcess allowed({sim, file, "--duration", "0.2", "--clock", "fast",
                        "--lcm-url", TestLcmUrl(7816), "--allow-overlap"},
                       dir + "/allowed.txt");
  EXPECT_EQ(allowed.Wait(60), 0) << allowed.Output();
}

}  // namespace
}  // namespace mrsim

// The stock LCM tools work with what mrsim-sim publishes: lcm-logger
// records it, lcm-logplayer replays it, and our lcm-spy launcher finds our
// types.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/sim_process/sim_client.h"

namespace mrsim::testing {
namespace {

bool Exists(const std::string& path) { return std::filesystem::exists(path); }

TEST(SimProcessTools, LcmLoggerRecordsTheSimAndLogplayerReplaysIt) {
  if (!Exists("/usr/bin/lcm-logger") || !Exists("/usr/bin/lcm-logplayer")) {
    GTEST_SKIP() << "liblcm-bin not installed";
  }
  const std::string dir = TempDir("sim_logger");
  const std::string scenario = TestScenarioPath(dir);
  const std::string robot = ReadScenarioFile(scenario).robots.at(0).name;
  const std::string log = dir + "/run.lcmlog";
  {
    SimClient client(TestLcmUrl(7606));
    ChildProcess logger(
        {"/usr/bin/lcm-logger", "-f", "--lcm-url=" + TestLcmUrl(7606), log},
        dir + "/logger.out");
    ChildProcess sim({SimBinary(), scenario, "--lcm-url", TestLcmUrl(7606),
                      "--clock", "realtime", "--rate", "50"},
                     dir + "/sim.log");
    ASSERT_TRUE(
        client.WaitFor([&] { return client.states_received() > 30; }, 10.0));
    EXPECT_EQ(sim.Stop(5.0), 0);
    logger.Signal(SIGINT);
    EXPECT_EQ(logger.Wait(5.0), 0) << logger.Output();
  }
  ASSERT_TRUE(Exists(log));
  EXPECT_GT(std::filesystem::file_size(log), 30u * 2000u);

  // Replayed on another port, the states decode as robot_state_t.
  SimClient replay(TestLcmUrl(7608));
  ChildProcess player({"/usr/bin/lcm-logplayer", "--speed=4",
                       "--lcm-url=" + TestLcmUrl(7608), log},
                      dir + "/player.out");
  ASSERT_TRUE(
      replay.WaitFor([&] { return replay.states_received() > 10; }, 10.0))
      << player.Output();
  EXPECT_EQ(replay.states().begin()->first, robot);
  EXPECT_TRUE(replay.WaitFor([&] { return replay.status().has_value(); }, 5.0));
}

// "Found N LCM types" from lcm.spy.Spy with the given classpath; -1 if not
// printed. Without a display Spy stops right after scanning.
int SpyTypeCount(const std::vector<std::string>& argv, const std::string& out) {
  ChildProcess spy(argv, out);
  spy.Wait(60.0);
  const std::string text = spy.Output();
  std::smatch m;
  if (std::regex_search(text, m, std::regex("Found ([0-9]+) LCM types"))) {
    return std::stoi(m[1]);
  }
  return -1;
}

TEST(SimProcessTools, LcmSpyLauncherDecodesOurTypes) {
  const std::string lcm_jar = "/usr/share/java/lcm.jar";
  const std::string launcher = BinaryPath("tools/mrsim-lcm-spy");
  if (!Exists(lcm_jar) || std::system("command -v java >/dev/null") != 0) {
    GTEST_SKIP() << "no java or lcm.jar";
  }
  if (!Exists(BinaryPath("lcmtypes/mrsim_lcmtypes.jar"))) {
    GTEST_SKIP() << "types jar not built (no JDK at configure time)";
  }
  const std::string dir = TempDir("sim_spy");
  // Without a display lcm-spy scans the types, then stops (the launcher
  // itself would stop first, saying there is no display, unless asked).
  unsetenv("DISPLAY");
  setenv("MRSIM_SPY_HEADLESS", "1", 1);
  const int ours = SpyTypeCount({launcher, "--lcm-url", TestLcmUrl(7607)},
                                dir + "/ours.out");
  const int stock =
      SpyTypeCount({"/bin/sh", "-c",
                    "exec java -Djava.awt.headless=true -cp " + lcm_jar +
                        " lcm.spy.Spy --lcm-url '" + TestLcmUrl(7607) + "'"},
                   dir + "/stock.out");
  int lcm_files = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(SourcePath("lcmtypes/mrsim"))) {
    if (entry.path().extension() == ".lcm") ++lcm_files;
  }
  ASSERT_GE(stock, 0) << "lcm.spy.Spy did not scan types";
  EXPECT_EQ(ours - stock, lcm_files);
  std::ifstream in(dir + "/ours.out");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str().find("Xincgc"), std::string::npos) << text.str();
}

}  // namespace
}  // namespace mrsim::testing

// mrsim-opt --controller mlp:8 as a user runs it (the flat task, CMA-ES,
// two local threads): three generations whose best so far never falls, a
// best_network.xml that mrsim-nn runs, and that network replayed against
// mrsim-sim in lockstep moves the robot exactly as far as the episode's
// fitness says.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim_core/physics/checkpoint.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::TempDir;
using testing::TestLcmUrl;

std::vector<std::vector<std::string>> ReadCsv(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(MlpOpt, BestNetworkReplayedByMrsimNnGivesTheEpisodesFitness) {
  const std::string dir = TempDir("mlp_opt_flat");
  const std::string out = dir + "/run";
  ChildProcess opt({BinaryPath("optimizer/process/mrsim-opt"), "--task", "flat",
                    "--controller", "mlp:8", "--algorithm", "cmaes",
                    "--population", "4", "--generations", "3", "--episode", "3",
                    "--workers", "local:2", "--seed", "7", "--out", out},
                   dir + "/opt.log");
  ASSERT_EQ(opt.Wait(600), 0) << opt.Output();

  const auto rows = ReadCsv(out + "/generations.csv");
  ASSERT_EQ(rows.size(), 4u) << "a header and three generations";
  ASSERT_EQ(rows[0][4], "best_so_far");
  double best = -1e300;
  for (size_t r = 1; r < rows.size(); ++r) {
    const double so_far = std::strtod(rows[r][4].c_str(), nullptr);
    EXPECT_GE(so_far, best) << "generation " << rows[r][0];
    best = so_far;
  }

  // The best network in lockstep with the simulator, on the best body.
  const std::string scenario = out + "/best_scenario.xml";
  const std::string url = TestLcmUrl(7977);
  ChildProcess nn({BinaryPath("nn_controller/process/mrsim-nn"), "--robot",
                   "snake", "--net", out + "/best_network.xml", "--lcm-url",
                   url, "--name", "nn", "--exit-with-sim"},
                  dir + "/nn.log");
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"), scenario,
                    "--lcm-url", url, "--clock", "lockstep", "--controllers",
                    "nn", "--duration", "3", "--lockstep-timeout", "20",
                    "--checkpoint-on-exit", dir + "/final.checkpoint"},
                   dir + "/sim.log");
  ASSERT_EQ(sim.Wait(120), 0) << sim.Output();
  EXPECT_EQ(nn.Wait(30), 0) << nn.Output();
  EXPECT_NE(nn.Output().find("answered 301 states"), std::string::npos)
      << nn.Output();

  // The flat task's fitness is the CoM's travel along +x.
  const Physics start(ReadScenarioFile(scenario));
  const auto end = LoadCheckpoint(dir + "/final.checkpoint");
  const double travel =
      end->ReadRobotState(0).com.x() - start.ReadRobotState(0).com.x();
  EXPECT_EQ(travel, best);
}

}  // namespace
}  // namespace mrsim

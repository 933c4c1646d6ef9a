// mrsim-nn as a real process over LCM on loopback: a network file run in
// lockstep with mrsim-sim ends where the same network run in process ends,
// bit for bit (so the fitness an optimiser's episode gave it is what the
// user sees); a broken file exits 2 naming its line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "nn_controller/network_file.h"
#include "optimizer/episode/episode_controller.h"
#include "optimizer/episode/mlp_episode_controller.h"
#include "sim_core/scenario/chain_builder.h"
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

const std::string kNn = "nn_controller/process/mrsim-nn";
const std::string kSim = "sim_core/sim_process/mrsim-sim";

TEST(NnProcess, LockstepRunEndsWhereTheInProcessRunEnds) {
  const std::string dir = TempDir("nn_process_lockstep");
  ChainOptions options;
  options.modules = 8;
  options.pattern = ChainPattern::kPitchYaw;
  Scenario scenario;
  scenario.robots.push_back(MakeChain(options));
  const std::string path = dir + "/snake.xml";
  WriteScenarioFile(scenario, path);

  MlpShape shape;
  shape.joints = Physics(ReadScenarioFile(path)).joint_count(0);
  shape.hidden = {6};
  shape.imu = true;
  std::vector<double> w(static_cast<size_t>(shape.WeightCount()));
  for (size_t i = 0; i < w.size(); ++i) w[i] = 1.5 * std::sin(2.1 * i + 0.4);
  const std::string net_path = dir + "/net.xml";
  WriteNetworkFile(MlpNetwork(shape, w, 1.7), net_path);

  const std::string url = TestLcmUrl(7975);
  ChildProcess nn({BinaryPath(kNn), "--robot", "snake", "--net", net_path,
                   "--lcm-url", url, "--name", "nn", "--exit-with-sim"},
                  dir + "/nn.log");
  ChildProcess sim(
      {BinaryPath(kSim), path, "--lcm-url", url, "--clock", "lockstep",
       "--controllers", "nn", "--duration", "3", "--lockstep-timeout", "20",
       "--checkpoint-on-exit", dir + "/final.checkpoint"},
      dir + "/sim.log");
  ASSERT_EQ(sim.Wait(120), 0) << sim.Output();
  EXPECT_EQ(nn.Wait(30), 0) << nn.Output();
  EXPECT_NE(nn.Output().find("answered 301 states"), std::string::npos)
      << nn.Output();

  // The same network from its file, as an optimiser's episode runs it.
  Physics physics(ReadScenarioFile(path));
  MlpEpisodeController network(ReadNetworkFile(net_path).network);
  const ControllerRunResult run = RunController(physics, 0, network, 3.0, 0.01);
  const auto final_state = LoadCheckpoint(dir + "/final.checkpoint");
  EXPECT_EQ(final_state->time(), physics.time());
  EXPECT_TRUE(final_state->SaveState() == physics.SaveState());
  const Eigen::Vector3d com = final_state->ReadRobotState(0).com;
  EXPECT_EQ(com.x(), run.com_end.x());
  EXPECT_EQ(com.y(), run.com_end.y());
  // It did move.
  EXPECT_GT((run.com_end - run.com_start).norm(), 1e-3);
}

TEST(NnProcess, ABrokenNetworkFileExits2NamingItsLine) {
  const std::string dir = TempDir("nn_process_broken");
  const std::string net_path = dir + "/net.xml";
  {
    std::ofstream out(net_path);
    out << "<network joints=\"2\" hidden=\"3\" clock=\"1\" imu=\"0\"\n"
           "  sensors=\"0\" range=\"1\" period=\"oops\">\n"
           "  <weights count=\"0\"></weights>\n</network>\n";
  }
  ChildProcess nn({BinaryPath(kNn), "--robot", "snake", "--net", net_path,
                   "--lcm-url", TestLcmUrl(7976)},
                  dir + "/nn.log");
  EXPECT_EQ(nn.Wait(30), 2) << nn.Output();
  EXPECT_NE(nn.Output().find(net_path + ":1: network/@period: expected a "
                                        "finite number, got 'oops'"),
            std::string::npos)
      << nn.Output();
}

}  // namespace
}  // namespace mrsim

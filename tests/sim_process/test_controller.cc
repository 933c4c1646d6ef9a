// A tiny controller process for the sim tests and benchmarks: answers every
// robot_state_t on <prefix>_STATE_* with a joint_command_t computed by
// WaveTargets. Usage:
//   mrsim-test-controller --lcm-url URL [--prefix P] [--name NAME]
#include <CLI/CLI.hpp>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "tests/sim_process/wave_law.h"

namespace {

class WaveController {
 public:
  WaveController(lcm::LCM& lcm, std::string prefix, std::string name)
      : lcm_(lcm), prefix_(std::move(prefix)), name_(std::move(name)) {}

  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/) {
    mrsim::robot_state_t state;
    if (!mrsim::DecodeMessage(rbuf, &state)) {
      ++malformed_;
      return;
    }
    mrsim::joint_command_t cmd;
    cmd.utime = state.utime;
    cmd.seq = ++seq_;
    cmd.robot = state.robot;
    cmd.sender = name_;
    cmd.state_seq = state.seq;
    cmd.target = mrsim::testing::WaveTargets(state);
    cmd.num_joints = static_cast<int32_t>(cmd.target.size());
    lcm_.publish(mrsim::CommandChannel(prefix_, state.robot), &cmd);
  }

  int64_t answered() const { return seq_; }
  int64_t malformed() const { return malformed_; }

 private:
  lcm::LCM& lcm_;
  std::string prefix_;
  std::string name_;
  int64_t seq_ = 0;
  int64_t malformed_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrsim test controller"};
  std::string url;
  std::string prefix = mrsim::kDefaultChannelPrefix;
  std::string name = "ctl";
  app.add_option("--lcm-url", url);
  app.add_option("--prefix", prefix);
  app.add_option("--name", name);
  CLI11_PARSE(app, argc, argv);
  try {
    mrsim::InstallStopHandlers();
    lcm::LCM lcm(url);
    if (!lcm.good()) {
      std::cerr << "test_controller: cannot open LCM " << url << "\n";
      return 1;
    }
    WaveController controller(lcm, prefix, name);
    lcm::Subscription* sub = lcm.subscribe(
        prefix + "_STATE_.*", &WaveController::OnState, &controller);
    sub->setQueueCapacity(1000);
    while (!mrsim::StopRequested()) mrsim::HandleFor(lcm, 100);
    std::cout << "test_controller " << name << ": answered "
              << controller.answered() << " states, malformed "
              << controller.malformed() << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "test_controller: " << e.what() << "\n";
    return 1;
  }
}

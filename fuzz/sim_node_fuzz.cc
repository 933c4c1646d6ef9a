// The simulator's core (SimNode) fed decodable but hostile commands and
// control requests: other robots' and strangers' commands, absurd sequence
// numbers, NaN and 1e308 targets, joint counts that disagree with the
// scenario, every control request with any argument, and clock jumps. It
// must neither crash nor let a non-finite value into the physics.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz/hostile_input.h"
#include "lcmtypes/runtime/channels.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"
#include "sim_core/sim_process/sim_node.h"

namespace {

mrsim::Scenario Snake() {
  mrsim::Scenario scenario;
  mrsim::ChainOptions chain;
  chain.name = "snake";
  chain.modules = 3;
  scenario.robots.push_back(mrsim::MakeChain(chain));
  return scenario;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim;
  static const Scenario scenario = Snake();
  fuzz::HostileInput in(data, size);
  SimOptions options;
  const uint8_t mode = in.Byte();
  options.clock = mode % 3 == 0   ? ClockMode::kLockstep
                  : mode % 3 == 1 ? ClockMode::kFast
                                  : ClockMode::kRealtime;
  if (options.clock == ClockMode::kLockstep) {
    options.controllers = {"c1"};
    options.actuation_delay = (mode >> 2) % 2;
    options.spin = false;
  }
  options.paused = (mode & 0x80) != 0;
  options.duration = 0.3;  // sim s: a fast clock stops by itself, soon
  std::ostringstream log;
  WallTime now{};
  SimNode node(std::make_unique<Physics>(scenario), options, log, now);
  SimOutbox out;
  node.Start(now, &out);
  const std::vector<std::string> robots = {"snake", "other"};
  const std::vector<std::string> senders = {"c1", "c2"};
  int64_t seq = 0;
  for (int op = 0; op < 64 && !in.empty() && !node.stopped(); ++op) {
    out.clear();
    switch (in.Byte() % 4) {
      case 0: {
        joint_command_t cmd = in.JointCommand(robots, senders, 2, seq);
        if (!fuzz::ThroughWire(&cmd)) break;
        const std::string robot = in.Bool() ? cmd.robot : "snake";
        node.OnCommand(cmd, CommandChannel(options.prefix, robot), now);
        break;
      }
      case 1: {
        sim_control_t control = in.SimControl(robots, senders);
        if (!fuzz::ThroughWire(&control)) break;
        node.OnControl(control, now, &out);
        break;
      }
      case 2:
        now = AfterSeconds(now, in.Step());
        node.Tick(now, &out);
        break;
      default:
        node.OnMalformed("fuzz");
        break;
    }
    for (const auto& [channel, message] : out.messages) {
      if (const auto* s = std::get_if<robot_state_t>(&message)) {
        seq = s->seq;
        for (const joint_state_t& j : s->joints) {
          if (!std::isfinite(j.angle)) std::abort();  // NaN got in
        }
      }
    }
  }
  if (!node.stopped()) node.Stop(StopReason::kSignal, now, &out);
  return 0;
}

// The gait controller's core (GaitNode) fed decodable but hostile states,
// gait commands, control requests and simulator statuses: other robots,
// absurd sequence numbers and times, NaN and 1e308 everywhere, joint
// counts that change from state to state. It must never crash nor send a
// non-finite joint target.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "fuzz/hostile_input.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/process/gait_node.h"
#include "gait_controller/process/joint_axes_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim;
  static const Gait kForward = *FindGaitPreset("forward");
  fuzz::HostileInput in(data, size);
  GaitNodeOptions options;
  options.robot = "snake";
  options.sender = "g";
  options.exit_with_sim = in.Bool();
  const std::string axes = in.Bool() ? "pitch" : "pitch-yaw";
  WallTime now{};
  GaitNode node(
      options, [axes](int n) { return JointAxesSpec(axes).Expand(n); },
      kForward, now);
  GaitOutbox out;
  node.Start(now, &out);
  const std::vector<std::string> robots = {"snake", "other"};
  int64_t seq = 0;
  for (int op = 0; op < 64 && !in.empty() && !node.done(); ++op) {
    out.clear();
    switch (in.Byte() % 6) {
      case 0: {
        robot_state_t state = in.RobotState(robots, 4, seq++);
        if (fuzz::ThroughWire(&state)) node.OnState(state, now, &out);
        break;
      }
      case 1: {
        gait_command_t command = in.GaitCommand(robots);
        if (fuzz::ThroughWire(&command)) node.OnGaitCommand(command, now, &out);
        break;
      }
      case 2: {
        sim_control_t control = in.SimControl(robots, {"ctl"});
        if (fuzz::ThroughWire(&control)) node.OnSimControl(control);
        break;
      }
      case 3: {
        sim_status_t status = in.SimStatus(seq);
        if (fuzz::ThroughWire(&status)) node.OnSimStatus(status, now, &out);
        break;
      }
      case 4:
        now = AfterSeconds(now, in.Step());
        node.Tick(now, &out);
        break;
      default:
        if (in.Bool()) {
          node.OnMalformedState();
        } else {
          node.OnMalformedGait(now, &out);
        }
        break;
    }
    for (const auto& [channel, message] : out.messages) {
      if (const auto* c = std::get_if<joint_command_t>(&message)) {
        for (double t : c->target) {
          if (!std::isfinite(t)) std::abort();  // a NaN target went out
        }
      }
    }
    node.TakeLog();
  }
  return 0;
}

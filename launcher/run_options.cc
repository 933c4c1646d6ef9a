#include "launcher/run_options.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/atomic_file.h"
#include "gait_controller/gait_file.h"

namespace mrsim {

std::vector<std::string> RunLcmArgs(const RunOptions& o) {
  std::vector<std::string> args;
  if (!o.lcm_url.empty()) args = {"--lcm-url", o.lcm_url};
  args.insert(args.end(), {"--prefix", o.prefix});
  return args;
}

RunOptions RunOptionsFromSettings(const std::optional<RunSettings>& run) {
  RunOptions o;
  if (!run) return o;
  o.clock = run->clock;
  o.rate = run->rate;
  o.speed = run->speed;
  o.controller = run->controller;
  o.gait = run->gait;
  o.external_name = run->external_name;
  return o;
}

bool UseTunedGait(const std::optional<RunSettings>& run,
                  const std::string& source, const std::string& path,
                  RunOptions* o) {
  if (!run || run->tuned_gait.empty() ||
      o->controller != ControllerKind::kGait) {
    return false;
  }
  ReadGaitString(run->tuned_gait, source);
  WriteFileAtomically(path, run->tuned_gait);
  o->gait = path;
  return true;
}

std::vector<ProcessSpec> RunProcessSpecs(const RunOptions& o) {
  if (o.scenario_path.empty()) {
    throw std::invalid_argument("run: save the design to a file first");
  }
  if (std::string(ToString(o.clock)) == "?") {
    throw std::invalid_argument("run: clock " +
                                std::to_string(static_cast<int>(o.clock)) +
                                " (expected " + ClockModes().Choices() + ")");
  }
  if (!(o.rate > 0) || !std::isfinite(o.rate)) {
    throw std::invalid_argument(
        fmt::format("run: rate {} Hz (expected > 0)", o.rate));
  }
  if (!(o.speed > 0) || !std::isfinite(o.speed)) {
    throw std::invalid_argument(fmt::format(
        "run: speed {} (expected a real-time factor > 0)", o.speed));
  }
  if (!(o.duration >= 0) || !std::isfinite(o.duration)) {
    throw std::invalid_argument(fmt::format(
        "run: duration {} s (expected >= 0; 0: until stopped)", o.duration));
  }
  std::vector<ProcessSpec> specs;
  std::vector<std::string> senders;
  ClockMode clock = o.clock;
  if (o.controller == ControllerKind::kExternal) {
    if (!ValidControllerName(o.external_name)) {
      throw std::invalid_argument(
          "run: external controller name '" + o.external_name +
          "' (expected 1-64 letters, digits, '-', '_' or '.', starting with "
          "a letter or digit)");
    }
    // The simulator waits for the user's program at every step.
    clock = ClockMode::kLockstep;
    senders.push_back(o.external_name);
  } else if (o.controller == ControllerKind::kGait ||
             o.controller == ControllerKind::kLua) {
    const bool lua = o.controller == ControllerKind::kLua;
    if (lua && o.lua_script.empty()) {
      throw std::invalid_argument("run: no Lua script to run");
    }
    for (const std::string& robot : o.robots) {
      ProcessSpec node;
      node.name = (lua ? "lua-" : "gait-") + robot;
      node.program = lua ? "mrsim-lua" : "mrsim-gait";
      node.ready_line = "listening on";  // both say so once subscribed
      if (lua) {
        node.args = {"--robot",    robot,
                     "--scenario", o.scenario_path,
                     "--script",   o.lua_script,
                     "--name",     node.name,
                     "--rate",     fmt::format("{:g}", o.rate)};
      } else {
        node.args = {"--robot", robot,  "--scenario", o.scenario_path,
                     "--gait",  o.gait, "--name",     node.name};
      }
      const auto lcm = RunLcmArgs(o);
      node.args.insert(node.args.end(), lcm.begin(), lcm.end());
      senders.push_back(node.name);
      specs.push_back(std::move(node));
    }
  } else {
    throw std::invalid_argument(
        "run: controller " + std::to_string(static_cast<int>(o.controller)) +
        " (expected " + ControllerKinds().Choices() + ")");
  }
  ProcessSpec sim;
  sim.name = "sim";
  sim.program = "mrsim-sim";
  sim.required = true;
  sim.args = {o.scenario_path, "--clock", ToString(clock), "--rate",
              fmt::format("{:g}", o.rate)};
  if (clock == ClockMode::kRealtime) {
    sim.args.insert(sim.args.end(), {"--speed", fmt::format("{:g}", o.speed)});
  }
  if (clock == ClockMode::kLockstep && !senders.empty()) {
    sim.args.push_back("--controllers");
    sim.args.insert(sim.args.end(), senders.begin(), senders.end());
  }
  if (o.paused) sim.args.push_back("--paused");
  if (o.duration > 0) {
    sim.args.insert(sim.args.end(),
                    {"--duration", fmt::format("{:g}", o.duration)});
  }
  if (!o.checkpoint_on_exit.empty()) {
    sim.args.insert(sim.args.end(),
                    {"--checkpoint-on-exit", o.checkpoint_on_exit});
  }
  if (o.allow_overlap) sim.args.push_back("--allow-overlap");
  const auto lcm = RunLcmArgs(o);
  sim.args.insert(sim.args.end(), lcm.begin(), lcm.end());
  specs.push_back(std::move(sim));
  return specs;
}

}  // namespace mrsim

#include "lua_controller/process/lua_node.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "lcmtypes/runtime/channels.h"

namespace mrsim {
namespace {

constexpr size_t kMaxLogLines = 1000;

}  // namespace

LuaNode::LuaNode(LuaNodeOptions options, std::unique_ptr<LuaScript> script,
                 std::function<std::vector<Axis>(int)> axes_for, WallTime now)
    : options_(std::move(options)),
      script_(std::move(script)),
      axes_for_(std::move(axes_for)),
      started_(now) {
  if (!(options_.rate >= 0) || !std::isfinite(options_.rate)) {
    throw std::invalid_argument("--rate must be >= 0");
  }
  if (!script_) throw std::invalid_argument("LuaNode: no script");
  rate_ = options_.rate;
}

void LuaNode::Log(std::string line) {
  if (log_.size() < kMaxLogLines) log_.push_back(std::move(line));
}

std::vector<std::string> LuaNode::TakeLog() {
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

WallTime LuaNode::Tick(WallTime now) {
  if (!sim_heard_ && !warned_no_simulator_ &&
      SecondsBetween(started_, now) >= kNoSimulatorWarning) {
    warned_no_simulator_ = true;
    Log(fmt::format(
        "warning: nothing from a simulator after {:.0f} s on {} (is "
        "mrsim-sim running, with the same --lcm-url and --prefix?)",
        kNoSimulatorWarning, StateChannel(options_.prefix, options_.robot)));
  }
  if (options_.exit_with_sim && !sim_stopped_) {
    if (!sim_heard_ && SecondsBetween(started_, now) >= kNoSimulatorGiveUp) {
      sim_stopped_ = true;
      gave_up_ = true;
      Log(fmt::format("no simulator heard in {:.0f} s (--exit-with-sim)",
                      kNoSimulatorGiveUp));
    } else if (sim_heard_ &&
               SecondsBetween(*sim_heard_, now) >= kSimulatorSilence) {
      sim_stopped_ = true;
      Log(
          fmt::format("the simulator has been silent for {:.0f} s "
                      "(--exit-with-sim): stopping",
                      kSimulatorSilence));
    }
  }
  return AfterSeconds(now, 0.5);
}

void LuaNode::OnSimStatus(const sim_status_t& status, WallTime now) {
  sim_heard_ = now;
  sim_clock_ = status.clock;
  if (status.mode == sim_status_t::STOPPING && !sim_stopped_) {
    sim_stopped_ = true;
    if (options_.exit_with_sim) Log("the simulator stopped (--exit-with-sim)");
  }
}

void LuaNode::OnState(const robot_state_t& state, WallTime now,
                      LuaOutbox* out) {
  sim_heard_ = now;
  if (!error_.empty()) return;
  try {
    HandleState(state, out);
  } catch (const LuaScriptError& e) {
    error_ = e.what();
  } catch (const std::exception& e) {
    ++counters_.messages_malformed;
    Log(fmt::format("state seq {} not answered: {}", state.seq, e.what()));
  }
  for (std::string& line : script_->TakePrinted()) {
    Log("print: " + std::move(line));
  }
}

void LuaNode::HandleState(const robot_state_t& state, LuaOutbox* out) {
  if (state.robot != options_.robot) {
    ++counters_.states_foreign;
    return;
  }
  if (!std::isfinite(state.sim_time) || state.sim_time < 0 ||
      state.sim_time > kMaxSimTime || state.num_joints < 0 ||
      static_cast<size_t>(state.num_joints) != state.joints.size()) {
    ++counters_.messages_malformed;
    return;
  }
  if (!axes_) {
    std::vector<Axis> axes;
    try {
      axes = axes_for_(state.num_joints);
      if (static_cast<int>(axes.size()) != state.num_joints) {
        throw std::invalid_argument(
            fmt::format("the joint axes list {} joints but robot {} has {}",
                        axes.size(), options_.robot, state.num_joints));
      }
    } catch (const std::invalid_argument& e) {
      error_ = e.what();
      return;
    }
    axes_.emplace();
    for (Axis a : axes) axes_->push_back(a == Axis::kYaw ? "yaw" : "pitch");
    Log(fmt::format("robot {}: {} joints; running {}", options_.robot,
                    state.num_joints, script_->name()));
  }
  if (static_cast<size_t>(state.num_joints) != axes_->size()) {
    ++counters_.messages_malformed;
    Log(fmt::format("state seq {} has {} joints, expected {}", state.seq,
                    state.num_joints, axes_->size()));
    return;
  }
  const auto recent = recent_.find(state.seq);
  if (recent != recent_.end()) {
    ++counters_.states_repeated;
    out->Add(CommandChannel(options_.prefix, options_.robot), recent->second);
    return;
  }
  if (have_last_ && state.seq < last_state_seq_) {
    ++counters_.states_skipped;
    return;
  }
  if (have_last_ && state.sim_time < last_time_) {
    // A reset or a loaded checkpoint: the script's t starts again.
    have_last_ = false;
  }
  const bool may_be_lockstep = sim_clock_.empty() || sim_clock_ == "lockstep";
  if (rate_ > 0 && state.seq == last_skipped_seq_ && may_be_lockstep) {
    Log(
        fmt::format("the simulator sent state seq {} again after it was "
                    "skipped (lockstep at more than --rate {} Hz): answering "
                    "every state from now on",
                    state.seq, rate_));
    rate_ = 0;
  }
  if (have_last_ && rate_ > 0 &&
      state.sim_time - last_time_ < 1.0 / rate_ - 1e-9) {
    ++counters_.states_skipped;
    last_skipped_seq_ = state.seq;
    return;
  }
  const size_t n = state.joints.size();
  input_.axes = *axes_;
  input_.angles.resize(n);
  input_.speeds.resize(n);
  input_.torques.resize(n);
  for (size_t j = 0; j < n; ++j) {
    input_.angles[j] = state.joints[j].angle;
    input_.speeds[j] = state.joints[j].speed;
    input_.torques[j] = state.joints[j].torque;
  }
  for (int i = 0; i < 3; ++i) {
    input_.com[i] = state.com[i];
    input_.com_velocity[i] = state.com_velocity[i];
  }
  for (int i = 0; i < 4; ++i) input_.orientation[i] = state.orientation[i];
  input_.heading = state.heading;
  input_.sensors.resize(state.sensor_modules.size());
  for (size_t k = 0; k < state.sensor_modules.size(); ++k) {
    const sensor_module_state_t& m = state.sensor_modules[k];
    LuaRobotState::Sensor& s = input_.sensors[k];
    s.has_force = m.has_force && std::isfinite(m.force);
    s.force = s.has_force ? m.force : 0.0;
    s.distances.clear();
    for (double d : m.distance) {
      if (std::isfinite(d)) s.distances.push_back(d);
    }
  }
  std::vector<double> targets = script_->Step(state.sim_time, input_);

  joint_command_t command;
  command.utime = state.utime;
  command.seq = command_seq_++;
  command.robot = options_.robot;
  command.sender = options_.sender;
  command.state_seq = state.seq;
  command.num_joints = static_cast<int32_t>(targets.size());
  command.target = std::move(targets);
  out->Add(CommandChannel(options_.prefix, options_.robot), command);
  recent_[state.seq] = std::move(command);
  while (recent_.size() > kRecentAnswers) recent_.erase(recent_.begin());
  last_state_seq_ = state.seq;
  last_time_ = state.sim_time;
  have_last_ = true;
  ++counters_.states_answered;
}

std::string LuaNode::Summary() const {
  const LuaNodeCounters& n = counters_;
  return fmt::format(
      "{}: answered {} states ({} repeated, {} skipped), malformed messages "
      "{}",
      options_.robot, n.states_answered, n.states_repeated, n.states_skipped,
      n.messages_malformed);
}

}  // namespace mrsim

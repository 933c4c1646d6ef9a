#include "gait_controller/process/gait_node.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "gait_controller/process/gait_command_apply.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"

namespace mrsim {

namespace {

constexpr size_t kMaxQueued = 100;
constexpr size_t kMaxLogLines = 1000;
constexpr int kStateQueueCapacity = 100;
constexpr int kGaitQueueCapacity = 100;

}  // namespace

GaitNode::GaitNode(lcm::LCM& lcm, GaitNodeOptions options,
                   std::function<std::vector<Axis>(int)> axes_for, Gait initial)
    : lcm_(lcm),
      options_(std::move(options)),
      axes_for_(std::move(axes_for)),
      initial_(std::move(initial)) {
  if (!(options_.rate >= 0) || !std::isfinite(options_.rate)) {
    throw std::invalid_argument("--rate must be >= 0");
  }
  lcm::Subscription* state = lcm_.subscribe(
      StateChannel(options_.prefix, options_.robot), &GaitNode::OnState, this);
  lcm::Subscription* gait = lcm_.subscribe(
      GaitChannel(options_.prefix, options_.robot), &GaitNode::OnGait, this);
  if (state == nullptr || gait == nullptr) {
    throw std::runtime_error("cannot subscribe to the LCM channels");
  }
  rate_ = options_.rate;
  state->setQueueCapacity(kStateQueueCapacity);
  gait->setQueueCapacity(kGaitQueueCapacity);
  subscriptions_ = {state, gait};
}

GaitNode::~GaitNode() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

void GaitNode::Log(std::string line) {
  if (log_.size() < kMaxLogLines) log_.push_back(std::move(line));
}

std::vector<std::string> GaitNode::TakeLog() {
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

std::string GaitNode::Describe() const {
  if (!controller_)
    return fmt::format("gait {} (waiting for the first state)", initial_.name);
  const GaitController& c = *controller_;
  return fmt::format("motion {} {:.2f}, gait {} ({})", ToString(c.motion()),
                     c.strength(), c.active_gait().name,
                     ToString(c.active_kind()));
}

void GaitNode::Apply(const gait_command_t& command, const std::string& source) {
  try {
    if (!controller_) {
      if (queued_.size() >= kMaxQueued) {
        ++counters_.commands_rejected;
        Log(
            fmt::format("rejected gait command from {}: too many before the "
                        "first state",
                        source));
        return;
      }
      queued_.emplace_back(command, source);
      return;
    }
    const std::string what = ApplyGaitCommand(command, controller_.get());
    ++counters_.commands_applied;
    Log(fmt::format("{}: {} -> {}", source, what, Describe()));
  } catch (const std::exception& e) {
    ++counters_.commands_rejected;
    Log(fmt::format("rejected gait command from {}: {} (keeping {})", source,
                    e.what(), Describe()));
  }
}

void GaitNode::OnGait(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  gait_command_t command;
  if (!DecodeMessage(rbuf, &command)) {
    ++counters_.messages_malformed;
    ++counters_.commands_rejected;
    Log("rejected a gait command that does not decode as gait_command_t");
    return;
  }
  if (!command.robot.empty() && command.robot != options_.robot) {
    ++counters_.commands_rejected;
    Log(fmt::format("rejected gait command for robot '{}' (this is {})",
                    command.robot, options_.robot));
    return;
  }
  Apply(command, command.sender.empty() ? "lcm" : command.sender);
}

void GaitNode::OnState(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  robot_state_t state;
  if (!DecodeMessage(rbuf, &state)) {
    ++counters_.messages_malformed;
    return;
  }
  try {
    HandleState(state);
  } catch (const std::exception& e) {
    ++counters_.messages_malformed;
    Log(fmt::format("state seq {} not answered: {}", state.seq, e.what()));
  }
}

void GaitNode::HandleState(const robot_state_t& state) {
  if (!error_.empty()) return;
  if (state.robot != options_.robot) {
    ++counters_.states_foreign;
    return;
  }
  if (!std::isfinite(state.sim_time) || state.sim_time < 0) {
    ++counters_.messages_malformed;
    return;
  }
  if (!controller_) {
    std::vector<Axis> axes;
    try {
      axes = axes_for_(state.num_joints);
      if (static_cast<int>(axes.size()) != state.num_joints) {
        throw std::invalid_argument(
            fmt::format("the joint axes list {} joints but robot {} has {}",
                        axes.size(), options_.robot, state.num_joints));
      }
      controller_ = std::make_unique<GaitController>(axes, options_.controller);
      controller_->SetGait(initial_);
    } catch (const std::exception& e) {
      controller_.reset();
      error_ = e.what();
      return;
    }
    Log(fmt::format("robot {}: {} joints; {}", options_.robot, state.num_joints,
                    Describe()));
    while (!queued_.empty()) {
      auto [command, source] = queued_.front();
      queued_.pop_front();
      Apply(command, source);
    }
  }
  if (state.num_joints != controller_->joint_count()) {
    ++counters_.messages_malformed;
    Log(fmt::format("state seq {} has {} joints, expected {}", state.seq,
                    state.num_joints, controller_->joint_count()));
    return;
  }
  if (have_last_ && state.seq == last_state_seq_) {
    // The simulator sent the state again (our answer may have been lost).
    ++counters_.states_repeated;
    lcm_.publish(CommandChannel(options_.prefix, options_.robot),
                 &last_command_);
    return;
  }
  if (have_last_ && state.seq < last_state_seq_) {
    ++counters_.states_skipped;
    return;
  }
  if (have_last_ && state.sim_time < last_time_) {
    Log(
        fmt::format("sim time went back to {} s (reset or checkpoint): the "
                    "gait starts again from rest",
                    state.sim_time));
    controller_->Reset();
    have_last_ = false;
  }
  if (rate_ > 0 && state.seq == last_skipped_seq_) {
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
  const double dt = have_last_ ? state.sim_time - last_time_ : 0.0;
  const std::vector<double>& targets = controller_->Update(dt);

  joint_command_t command;
  command.utime = state.utime;
  command.seq = command_seq_++;
  command.robot = options_.robot;
  command.sender = options_.sender;
  command.state_seq = state.seq;
  command.num_joints = static_cast<int32_t>(targets.size());
  command.target = targets;
  lcm_.publish(CommandChannel(options_.prefix, options_.robot), &command);

  last_command_ = std::move(command);
  last_state_seq_ = state.seq;
  last_time_ = state.sim_time;
  have_last_ = true;
  ++counters_.states_answered;
}

}  // namespace mrsim

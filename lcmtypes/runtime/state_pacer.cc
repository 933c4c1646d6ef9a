#include "lcmtypes/runtime/state_pacer.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

namespace mrsim {

StatePacer::StatePacer(std::string robot, std::string sender, double rate)
    : robot_(std::move(robot)), sender_(std::move(sender)), rate_(rate) {
  if (!(rate_ >= 0) || !std::isfinite(rate_)) {
    throw std::invalid_argument("--rate must be >= 0");
  }
}

StatePacer::Decision StatePacer::Decide(const robot_state_t& state,
                                        bool may_be_lockstep,
                                        std::string* note) {
  Decision d;
  const auto recent = recent_.find(state.seq);
  if (recent != recent_.end()) {
    // The simulator sent the state again (our answer may have been lost).
    d.verdict = Verdict::kRepeat;
    d.repeat = &recent->second;
    return d;
  }
  if (have_last_ && state.seq < last_state_seq_) {
    return d;
  }
  if (have_last_ && state.sim_time < last_time_) {
    d.restarted = true;
    have_last_ = false;
  }
  // Only lockstep waits for an answer; a paused sim re-sends its newest
  // state whatever its clock, and that one may have been skipped.
  if (rate_ > 0 && state.seq == last_skipped_seq_ && may_be_lockstep) {
    if (note != nullptr) {
      *note = fmt::format(
          "the simulator sent state seq {} again after it was skipped "
          "(lockstep at more than --rate {} Hz): answering every state from "
          "now on",
          state.seq, rate_);
    }
    rate_ = 0;
  }
  if (have_last_ && rate_ > 0 &&
      state.sim_time - last_time_ < 1.0 / rate_ - 1e-9) {
    last_skipped_seq_ = state.seq;
    return d;
  }
  d.verdict = Verdict::kAnswer;
  return d;
}

const joint_command_t& StatePacer::Answer(const robot_state_t& state,
                                          std::vector<double> targets) {
  joint_command_t command;
  command.utime = state.utime;
  command.seq = command_seq_++;
  command.robot = robot_;
  command.sender = sender_;
  command.state_seq = state.seq;
  command.num_joints = static_cast<int32_t>(targets.size());
  command.target = std::move(targets);
  joint_command_t& kept = recent_[state.seq] = std::move(command);
  while (recent_.size() > kRecentAnswers) {
    // After a restart the new seq may be the oldest kept: keep it.
    auto oldest = recent_.begin();
    if (oldest->first == state.seq) ++oldest;
    recent_.erase(oldest);
  }
  last_state_seq_ = state.seq;
  last_time_ = state.sim_time;
  have_last_ = true;
  return kept;
}

void StatePacer::Restore(bool have_last, double last_time) {
  have_last_ = have_last;
  last_time_ = last_time;
  recent_.clear();
}

}  // namespace mrsim

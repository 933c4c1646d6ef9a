#include "sim_core/sim_process/command_filter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lcmtypes/runtime/seq_gap.h"

namespace mrsim {
namespace {

// Accepted commands remembered per sender: a controller answers every state
// the simulator re-sends, and a pipelined simulator re-sends the two it
// awaits; mrsim-gait keeps its last eight answers.
constexpr size_t kRecentCommands = 8;

}  // namespace

const char* ToString(CommandVerdict verdict) {
  switch (verdict) {
    case CommandVerdict::kAccepted:
      return "accepted";
    case CommandVerdict::kWrongJointCount:
      return "wrong joint count";
    case CommandVerdict::kBadValue:
      return "non-finite or out-of-range target";
    case CommandVerdict::kUnknownRobot:
      return "unknown robot";
    case CommandVerdict::kStaleSeq:
      return "stale sequence number";
    case CommandVerdict::kNotController:
      return "sender is not a lockstep controller";
    case CommandVerdict::kRepeat:
      return "repeat of an accepted command";
    case CommandVerdict::kEmptyIgnored:
      return "answer without targets outside lockstep";
  }
  return "?";
}

CommandFilter::CommandFilter(std::vector<std::string> robots,
                             std::vector<int> joint_counts)
    : robots_(std::move(robots)),
      joint_counts_(std::move(joint_counts)),
      newest_state_seq_(robots_.size(), -1) {
  if (robots_.size() != joint_counts_.size()) {
    throw std::invalid_argument("CommandFilter: one joint count per robot");
  }
}

int CommandFilter::robot_index(const std::string& name) const {
  for (size_t i = 0; i < robots_.size(); ++i) {
    if (robots_[i] == name) return static_cast<int>(i);
  }
  return -1;
}

CommandVerdict CommandFilter::Check(const joint_command_t& cmd,
                                    const std::string& channel_robot,
                                    int64_t latest_state_seq, bool lockstep,
                                    const std::vector<std::string>& controllers,
                                    int64_t oldest_state_seq) {
  const int robot = robot_index(cmd.robot);
  if (robot < 0 || cmd.robot != channel_robot) {
    return CommandVerdict::kUnknownRobot;
  }

  // Gap accounting sees every decodable command of a known robot, valid or
  // not: a rejected command was received, a missing seq was not.
  SenderHistory& h = senders_[{robot, cmd.sender}];
  // Overflow-safe: a forged seq of INT64_MAX is no gap of 2^63 messages.
  if (h.seen) seq_gaps_ += SeqGap(h.last_seen_seq, cmd.seq);
  if (!h.seen || cmd.seq > h.last_seen_seq || cmd.seq < 0 ||
      SeqFarBehind(h.last_seen_seq, cmd.seq, 1000)) {
    // Forward, or a restarted sender (seq far back): follow it.
    h.last_seen_seq = cmd.seq;
  }
  h.seen = true;
  for (const joint_command_t& c : h.recent) {
    if (c.seq == cmd.seq && c.state_seq == cmd.state_seq &&
        c.target == cmd.target) {
      return CommandVerdict::kRepeat;
    }
  }

  if (lockstep && std::find(controllers.begin(), controllers.end(),
                            cmd.sender) == controllers.end()) {
    return CommandVerdict::kNotController;
  }
  const int expected = joint_counts_[robot];
  // num_joints says how many targets there are: lcm-gen's decode leaves a
  // reused message's old targets in place when it is 0.
  const bool empty = cmd.num_joints == 0;
  // Outside lockstep nobody waits for an answer, and an empty one taken as
  // the newest would make a real controller's answer to an older state look
  // stale: ignored before it touches any history.
  if (empty && expected > 0 && !lockstep) return CommandVerdict::kEmptyIgnored;
  if (!empty && (cmd.num_joints != expected ||
                 static_cast<int>(cmd.target.size()) != expected)) {
    return CommandVerdict::kWrongJointCount;
  }
  for (int j = 0; j < cmd.num_joints; ++j) {
    const double t = cmd.target[j];
    if (!std::isfinite(t) || std::abs(t) > kMaxCommandTarget) {
      return CommandVerdict::kBadValue;
    }
  }

  if (cmd.state_seq > latest_state_seq) return CommandVerdict::kStaleSeq;
  if (cmd.state_seq < 0) {
    if (lockstep) return CommandVerdict::kStaleSeq;
    // Open loop: only the sender's own numbering orders its commands.
    if (h.accepted && h.last_state_seq < 0 && cmd.seq <= h.last_seq) {
      return CommandVerdict::kStaleSeq;
    }
  } else {
    if (lockstep) {
      // Lockstep applies an answer only to a state being waited for; each
      // state has its own answers, so several controllers of one robot,
      // and one controller answering a re-sent state late, may answer in
      // any order.
      const int64_t oldest =
          oldest_state_seq < 0 ? latest_state_seq : oldest_state_seq;
      if (cmd.state_seq < oldest) return CommandVerdict::kStaleSeq;
    } else if (cmd.state_seq < newest_state_seq_[robot]) {
      return CommandVerdict::kStaleSeq;
    }
    if (h.accepted && cmd.state_seq == h.last_state_seq &&
        cmd.seq <= h.last_seq) {
      return CommandVerdict::kStaleSeq;  // duplicate or reordered answer
    }
    if (!empty) {
      newest_state_seq_[robot] =
          std::max(newest_state_seq_[robot], cmd.state_seq);
    }
  }
  h.accepted = true;
  h.last_state_seq = cmd.state_seq;
  h.last_seq = cmd.seq;
  h.recent.push_back(cmd);
  if (h.recent.size() > kRecentCommands) h.recent.pop_front();
  return CommandVerdict::kAccepted;
}

}  // namespace mrsim

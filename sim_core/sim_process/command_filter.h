// Decides whether a decoded joint command may move a robot: right robot,
// right joint count, finite targets within |pi|, and a sequence that is not
// stale. Pure bookkeeping (no LCM, no physics) so the rules are testable.
// A command without targets (num_joints 0) is an answer that moves nothing:
// how a lockstep party that only watches (mrsim-camera) keeps the simulator
// waiting until it has seen each state.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mrsim/joint_command_t.hpp"

namespace mrsim {

enum class CommandVerdict {
  kAccepted,
  kWrongJointCount,  // num_joints (or the array) differs from the robot's
  kBadValue,         // NaN, Inf or |target| > kMaxCommandTarget
  kUnknownRobot,     // robot not in the scenario, or not the channel's robot
  kStaleSeq,         // answers an older state, repeats a seq, or a bad seq
  kNotController,    // lockstep: sender not among --controllers
  kRepeat,        // a command this sender had accepted, again (its answer to a
                  // re-sent state): not an error, and it moves nothing again
  kEmptyIgnored,  // no targets (num_joints 0) outside lockstep: a lockstep
                  // answer sent anyway; moves nothing, not an error
};
const char* ToString(CommandVerdict verdict);

// Targets beyond this (rad) are not angles a hinge can mean (degrees sent by
// mistake, garbage); within it the physics clamps them to the joint limits,
// which is how gaits with large amplitudes saturate.
inline constexpr double kMaxCommandTarget = 3.14159265358979323846;

class CommandFilter {
 public:
  // Robots in scenario order with their hinge counts.
  CommandFilter(std::vector<std::string> robots, std::vector<int> joint_counts);

  // Index of the robot named `name`, or -1.
  int robot_index(const std::string& name) const;

  // Judges `cmd` received on the command channel of `channel_robot`.
  // latest_state_seq: the seq of the newest state published. lockstep:
  // commands must answer a state (state_seq >= 0) and come from one of
  // `controllers`, answering a state in [oldest_state_seq, latest] (-1:
  // the latest only; pipelined lockstep also takes the state still
  // awaited). Accepted commands update the sequence history. A command
  // without targets is accepted in lockstep (an answer that moves nothing:
  // the caller records it and applies nothing) and kEmptyIgnored otherwise.
  CommandVerdict Check(const joint_command_t& cmd,
                       const std::string& channel_robot,
                       int64_t latest_state_seq, bool lockstep,
                       const std::vector<std::string>& controllers,
                       int64_t oldest_state_seq = -1);

  // Commands a sender numbered but we never saw (gaps in its seq).
  int64_t seq_gaps() const { return seq_gaps_; }

 private:
  struct SenderHistory {
    int64_t last_seen_seq = -1;
    bool seen = false;
    int64_t last_state_seq = -1;
    int64_t last_seq = -1;
    bool accepted = false;
    // The last commands accepted, to tell a repeat from a stale command.
    std::deque<joint_command_t> recent;
  };

  std::vector<std::string> robots_;
  std::vector<int> joint_counts_;
  std::vector<int64_t> newest_state_seq_;  // per robot, -1 = none yet
  std::map<std::pair<int, std::string>, SenderHistory> senders_;
  int64_t seq_gaps_ = 0;
};

}  // namespace mrsim

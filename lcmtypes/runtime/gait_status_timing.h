// The contract of gait_status_t between a controller that takes steering
// and those who steer: a controller that answers gait commands (mrsim-gait,
// mrsim-lua with a script's on_gait_command, a program of one's own) sends
// its gait status at least every kGaitStatusInterval; the studio and
// mrsim-ctl take a robot heard for kGaitStatusWait without one to be
// driven by a controller that takes no steering. One place, so the two
// sides cannot drift apart.
#pragma once

namespace mrsim {

inline constexpr double kGaitStatusInterval = 1.0;  // wall s
// Two and a half intervals: one status lost on a busy network does not
// make a steerable robot look unsteerable.
inline constexpr double kGaitStatusWait = 2.5 * kGaitStatusInterval;  // s

}  // namespace mrsim

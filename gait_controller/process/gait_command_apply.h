// Applies a gait_command_t (LCM) to a gait controller, all or nothing: a
// command with any bad part changes nothing.
#pragma once

#include <string>

#include "gait_controller/gait_controller.h"
#include "mrsim/gait_command_t.hpp"

namespace mrsim {

// Throws std::invalid_argument (or GaitFileError for a gait that cannot be
// found or read) naming the bad field; the controller is then unchanged.
// Returns a one-line description of what changed.
std::string ApplyGaitCommand(const gait_command_t& command,
                             GaitController* controller);

// What a command asks for, in words ("gait sidewind, motion backward
// 1.00"), for one not applied yet.
std::string DescribeGaitCommand(const gait_command_t& command);

}  // namespace mrsim

// What each key of mrsim-gait --keyboard asks for, as a gait command (the
// same path as LCM gait commands, so keyboard changes are acknowledged and
// published in the gait status like any other).
#pragma once

#include <optional>

#include "gait_controller/gait_controller.h"
#include "gait_controller/process/keyboard.h"
#include "mrsim/gait_command_t.hpp"

namespace mrsim {

// The key help line.
const char* KeyHelp();

// The command for `key` given the current controller (null before the first
// state); nullopt for keys that change nothing. Sets *quit for q, *help for
// h and ?.
std::optional<gait_command_t> KeyCommand(const Key& key,
                                         const GaitController* controller,
                                         bool* quit, bool* help);

}  // namespace mrsim

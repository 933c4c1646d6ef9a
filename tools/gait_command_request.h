// Turns "gait ROBOT [gait NAME] [motion M] [strength S] [direction F T]"
// into a gait_command_t, checking what the shell can check (motion names,
// ranges) so a typo fails at once; mrsim-gait checks the rest (gait names
// and files) and says so in its gait status.
#pragma once

#include <string>
#include <vector>

#include "mrsim/gait_command_t.hpp"

namespace mrsim {

// words[0] is "gait". Throws std::invalid_argument naming the word that is
// wrong and what was expected. seq, utime and sender are left for the
// caller.
gait_command_t ParseGaitRequest(const std::vector<std::string>& words);

const char* GaitRequestUsage();

}  // namespace mrsim

// Turns a shell command ("pause", "step 10", "save run.checkpoint", ...)
// into a sim_control_t, so mrsim-ctl and scripts share one parser.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "mrsim/sim_control_t.hpp"

namespace mrsim {

// Throws std::invalid_argument naming the word that is wrong and what was
// expected. seq, utime and sender are left for the caller.
sim_control_t ParseSimControl(const std::vector<std::string>& words);

// "pause | resume | step N | reset | save PATH | load PATH | speed S | quit".
const char* SimControlUsage();

}  // namespace mrsim

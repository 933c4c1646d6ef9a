// mrsim-view as library code: opens the window or the off-screen context,
// builds the viewer, and runs the frame pump over a live LCM stream (states
// received on their own thread) or an .lcmlog, printing progress and a
// summary. main parses the flags, owns the SignedLcm and calls RunView.
#pragma once

#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "lcmtypes/runtime/signed_lcm.h"
#include "viewer/process/view_options.h"

namespace mrsim {

// Bad input: --window without a display, a file that is not an LCM log, a
// log with no state of the scenario's robots (mrsim-view exits with 2).
class ViewInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Checks what can be checked before anything opens (a display for
// --window). Throws ViewInputError.
void CheckViewOptions(const ViewOptions& options);

// Renders until the log ends, --max-frames, a stop request or the window
// closes. `lcm` is the open connection of a live run (unused with
// --from-log). Nothing is written unless a frame is rendered. Returns 0;
// throws ViewInputError, ScenarioError, std::invalid_argument (bad input)
// or std::runtime_error.
int RunView(const ViewOptions& options, SignedLcm* lcm, std::FILE* err);

}  // namespace mrsim

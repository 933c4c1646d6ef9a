// mrsim-ctl's conversations: a control request to mrsim-sim, a gait command
// to one mrsim-gait, or one status line. Each waits for the other side's
// heartbeat before sending (a message sent before the peer subscribed is
// lost), sends once, and waits for the acknowledgement that names this
// sender and seq, so "done" is printed only for what was carried out.
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "lcmtypes/runtime/signed_lcm.h"

namespace mrsim {

struct CtlOptions {
  std::string prefix = "MRSIM";
  double timeout = 5.0;  // s to wait for the heartbeat and again the answer
  // This run's sender name (one per process, seq from 1: the simulator
  // counts gaps in a sender's seq as lost requests).
  std::string sender;
};

// `mrsim-ctl --help`'s description: every command it takes.
std::string CtlHelp();

// The exit status: 0 done, 1 refused or no answer, 2 bad words (thrown as
// std::invalid_argument before anything is sent).
int RunCtl(SignedLcm& lcm, const std::vector<std::string>& words,
           const CtlOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mrsim

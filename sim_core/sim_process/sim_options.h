// How mrsim-sim runs: clock mode, rates, lockstep controllers, channel
// prefix. Filled from the command line by main.
#pragma once

#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/clock_mode.h"

namespace mrsim {

inline constexpr int kMaxActuationDelay = 8;

struct SimOptions {
  std::string prefix = kDefaultChannelPrefix;
  ClockMode clock = ClockMode::kRealtime;
  double speed = 1.0;   // real-time factor for the realtime clock
  double rate = 100.0;  // Hz: state publication rate = control rate
  std::vector<std::string> controllers;  // lockstep: senders to wait for
  double lockstep_timeout = 2.0;         // s (wall) before warning
  // Lockstep: the answer to state k acts from period k + actuation_delay
  // (0: strict; 1: pipelined, the next period's physics overlaps the round
  // trip). At most kMaxActuationDelay.
  int actuation_delay = 0;
  // Lockstep: states go out through a thread that waits for them spinning
  // at idle priority (PublishThread::Wait::kSpin) rather than asleep.
  bool spin = true;
  double duration = 0.0;  // s of sim time; 0 = forever
  bool paused = false;
  bool publish_state = true;  // false: batch runs that nobody watches
  std::string checkpoint_on_exit;
  // This simulator's name in its statuses ("host:pid"; SimServer fills it
  // in when empty).
  std::string instance;

  // Throws std::invalid_argument naming the bad option.
  void Validate() const;
};

}  // namespace mrsim

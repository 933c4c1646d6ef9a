// Whether a controller node's simulator is there: the one warning when
// nothing is heard soon after starting (a wrong --lcm-url or --prefix), and
// with --exit-with-sim when the node should stop (the simulator said it
// stops, went silent, or never came). Shared by every controller node
// (mrsim-gait, mrsim-lua) so they behave and word it alike.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "lcmtypes/runtime/clock_mode.h"
#include "lcmtypes/runtime/outbox.h"
#include "mrsim/sim_status_t.hpp"

namespace mrsim {

class SimulatorWatch {
 public:
  // Nothing from the simulator this long after starting: the prefix or the
  // LCM URL is probably wrong, said once (wall s).
  static constexpr double kNoSimulatorWarning = 5.0;
  // With exit_with_sim, a simulator silent this long is gone (killed, or
  // its host lost); it sends a status every 0.5 s even when paused (wall s).
  static constexpr double kSimulatorSilence = 5.0;
  // With exit_with_sim, no simulator heard at all this long after starting:
  // it failed to start (or the URL or prefix is wrong) and the node stops
  // rather than wait forever in a batch script (wall s; docs/gait.md).
  static constexpr double kNoSimulatorGiveUp = 30.0;

  // `channels`: what the node listens on, for the warning.
  SimulatorWatch(std::string channels, bool exit_with_sim, WallTime now);

  // A state or anything else from the simulator.
  void Heard(WallTime now) { heard_ = now; }
  // Its status: heard, its clock, and whether it is stopping.
  void OnStatus(const sim_status_t& status, WallTime now,
                std::vector<std::string>* log);
  // The warning and, with exit_with_sim, a silent or absent simulator.
  void Tick(WallTime now, std::vector<std::string>* log);

  // The simulator stopped (or, with exit_with_sim, is taken as stopped).
  bool stopped() const { return stopped_; }
  // Stopped because no simulator was heard within kNoSimulatorGiveUp.
  bool gave_up() const { return gave_up_; }
  // Its clock: none until heard or when its word is unknown (a newer
  // simulator), which may be lockstep.
  const std::optional<ClockMode>& clock() const { return clock_; }
  bool may_be_lockstep() const {
    return !clock_ || *clock_ == ClockMode::kLockstep;
  }

 private:
  std::string channels_;
  bool exit_with_sim_;
  WallTime started_;
  std::optional<WallTime> heard_;  // the last state or status
  std::optional<ClockMode> clock_;
  bool warned_ = false;
  bool stopped_ = false;
  bool gave_up_ = false;
};

}  // namespace mrsim

#include "lcmtypes/runtime/simulator_watch.h"

#include <fmt/format.h>

#include <utility>

namespace mrsim {

SimulatorWatch::SimulatorWatch(std::string channels, bool exit_with_sim,
                               WallTime now)
    : channels_(std::move(channels)),
      exit_with_sim_(exit_with_sim),
      started_(now) {}

void SimulatorWatch::OnStatus(const sim_status_t& status, WallTime now,
                              std::vector<std::string>* log) {
  heard_ = now;
  clock_ = ClockModes().Find(status.clock);
  if (status.mode == sim_status_t::STOPPING && !stopped_) {
    stopped_ = true;
    if (exit_with_sim_)
      log->push_back("the simulator stopped (--exit-with-sim)");
  }
}

void SimulatorWatch::Tick(WallTime now, std::vector<std::string>* log) {
  if (!heard_ && !warned_ &&
      SecondsBetween(started_, now) >= kNoSimulatorWarning) {
    warned_ = true;
    log->push_back(fmt::format(
        "warning: nothing from a simulator after {:.0f} s on {} (is "
        "mrsim-sim running, with the same --lcm-url and --prefix?)",
        kNoSimulatorWarning, channels_));
  }
  if (!exit_with_sim_ || stopped_) return;
  if (!heard_ && SecondsBetween(started_, now) >= kNoSimulatorGiveUp) {
    stopped_ = true;
    gave_up_ = true;
    log->push_back(fmt::format(
        "no simulator heard in {:.0f} s (--exit-with-sim): giving up (did "
        "mrsim-sim fail to start, or does it use another --lcm-url or "
        "--prefix?)",
        kNoSimulatorGiveUp));
  } else if (heard_ && SecondsBetween(*heard_, now) >= kSimulatorSilence) {
    stopped_ = true;
    log->push_back(fmt::format(
        "the simulator has been silent for {:.0f} s (--exit-with-sim): "
        "stopping",
        kSimulatorSilence));
  }
}

}  // namespace mrsim

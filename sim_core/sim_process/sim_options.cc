#include "sim_core/sim_process/sim_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mrsim {

void SimOptions::Validate() const {
  if (prefix.empty())
    throw std::invalid_argument("--prefix: must not be empty");
  if (!(std::isfinite(speed) && speed > 0)) {
    throw std::invalid_argument("--speed: expected a number > 0");
  }
  if (!(std::isfinite(rate) && rate > 0)) {
    throw std::invalid_argument("--rate: expected a rate in Hz > 0");
  }
  if (!(std::isfinite(lockstep_timeout) && lockstep_timeout > 0)) {
    throw std::invalid_argument("--lockstep-timeout: expected seconds > 0");
  }
  if (!(std::isfinite(duration) && duration >= 0)) {
    throw std::invalid_argument("--duration: expected seconds >= 0");
  }
  if (actuation_delay < 0 || actuation_delay > kMaxActuationDelay) {
    throw std::invalid_argument("--actuation-delay: expected 0.." +
                                std::to_string(kMaxActuationDelay) + ", got " +
                                std::to_string(actuation_delay));
  }
  if (actuation_delay > 0 && clock != ClockMode::kLockstep) {
    throw std::invalid_argument(
        "--actuation-delay needs --clock lockstep (the other clocks apply "
        "the newest command whenever it arrives)");
  }
  if (!controllers.empty() && clock != ClockMode::kLockstep) {
    // Only lockstep waits for named controllers; under another clock the
    // list would be ignored and the run silently real-time or fast.
    throw std::invalid_argument(
        "--controllers needs --clock lockstep (the " +
        std::string(ToString(clock)) +
        " clock waits for no controller; every sender's commands apply)");
  }
  if (clock == ClockMode::kLockstep) {
    if (controllers.empty()) {
      throw std::invalid_argument(
          "--clock lockstep needs --controllers NAME,... (the senders to "
          "wait for)");
    }
    if (!publish_state) {
      throw std::invalid_argument(
          "--no-state cannot be used with --clock lockstep (controllers "
          "answer the state)");
    }
  }
  for (const std::string& c : controllers) {
    if (c.empty()) throw std::invalid_argument("--controllers: empty name");
  }
}

}  // namespace mrsim

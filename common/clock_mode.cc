#include "common/clock_mode.h"

namespace mrsim {

const EnumTable<ClockMode>& ClockModes() {
  static const EnumTable<ClockMode> kModes(
      "--clock", {{ClockMode::kRealtime, "realtime"},
                  {ClockMode::kFast, "fast"},
                  {ClockMode::kLockstep, "lockstep"}});
  return kModes;
}

}  // namespace mrsim

// The simulator's clock as an enum with one table of words: mrsim-sim's
// --clock flag, sim_status_t.clock, a scenario's saved run settings, the
// studio's run form and the gait controller (which only answers every state
// under lockstep) parse and print it here, so the words are written once.
#pragma once

#include <string>

#include "common/enum_table.h"

namespace mrsim {

// realtime: paced to the wall clock times `speed`. fast: as fast as the CPU
// allows. lockstep: each control period waits for an answer to the current
// state from every controller, so runs are deterministic.
enum class ClockMode { kRealtime, kFast, kLockstep };
// The clock's words (sim_status_t.clock carries them too).
const EnumTable<ClockMode>& ClockModes();
inline const char* ToString(ClockMode mode) { return ClockModes().Name(mode); }
// Throws std::invalid_argument naming `field` and the accepted values.
inline ClockMode ParseClockMode(const std::string& text,
                                const std::string& field = "--clock") {
  return ClockModes().Parse(text, field);
}

}  // namespace mrsim

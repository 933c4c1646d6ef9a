// How a design is meant to be run, saved with it (<run> in a scenario
// file): the clock, the control rate, the real-time factor and who drives
// the robots (the gait, a Lua script carried in the file, or an external
// controller by name). The studio's Run and `mrsim-sim FILE` start from
// these; a file without them runs as mrsim-sim's flags default.
#pragma once

#include <cstddef>
#include <string>

#include "common/clock_mode.h"
#include "common/enum_table.h"
#include "common/input_limits.h"

namespace mrsim {

// Who drives the robots. gait: mrsim-gait per robot; lua: mrsim-lua per
// robot running RunSettings::lua_script; external: nothing is started, the
// simulator runs in lockstep waiting for the program named external_name.
enum class ControllerKind { kGait, kLua, kExternal };
// The words of ControllerKind ("gait", "lua", "external"), in enum order.
const EnumTable<ControllerKind>& ControllerKinds();
inline const char* ToString(ControllerKind kind) {
  return ControllerKinds().Name(kind);
}

// Bounds on the text a <run> element carries (docs/scenario.md, "Limits");
// the Lua script's, kMaxLuaScriptBytes, is common/input_limits.h's.
inline constexpr size_t kMaxRunNameBytes = 64;    // gait and controller names
inline constexpr double kMaxControlRate = 10000;  // Hz
inline constexpr double kMaxRealtimeFactor = 1000;
// A gait file's text (gait_controller/gait_file.h): seven numbers, a CPG
// and a joint override per hinge of the largest robot fit in far less.
inline constexpr size_t kMaxTunedGaitBytes = size_t{64} << 10;

struct RunSettings {
  ClockMode clock = ClockMode::kRealtime;
  double rate = 100;  // Hz: state publication rate = control rate
  double speed = 1;   // real-time factor (realtime clock)
  ControllerKind controller = ControllerKind::kGait;
  std::string gait = "forward";  // the gait each robot starts with
  // The gait as tuned in the studio's Run panel, the text of a gait file
  // (gait_controller/gait_file.h), carried so the design runs as it was
  // left; empty: the preset or file `gait` names. For controller gait.
  std::string tuned_gait;
  std::string lua_script;     // the Lua source itself, for kLua
  std::string external_name;  // the sender mrsim-sim waits for
};

// A controller name mrsim-sim --controllers can list: 1-64 letters,
// digits, '-', '_' or '.', not starting with '-' or '.'.
bool ValidControllerName(const std::string& name);

// Field by field, as the schema lists them (defined with the scenario's).
bool operator==(const RunSettings& a, const RunSettings& b);
inline bool operator!=(const RunSettings& a, const RunSettings& b) {
  return !(a == b);
}

}  // namespace mrsim

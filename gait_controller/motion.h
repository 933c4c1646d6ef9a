// The motions a gait controller can be commanded to perform, and the kind of
// gait each one runs (domain.md section 4).
#pragma once

#include <optional>
#include <string>

namespace mrsim {

enum class Motion {
  kForward,
  kBackward,
  kTurnLeft,
  kTurnRight,
  kSidewindLeft,
  kSidewindRight,
  kRoll,
  kStop,
};

// Which gait a motion runs: forward, backward and the turns share the
// linear (travelling-wave) gait; sidewinding and rolling have their own.
enum class GaitKind { kLinear, kSidewind, kRoll };

// "forward", "backward", "turn-left", "turn-right", "sidewind-left",
// "sidewind-right", "roll", "stop".
const char* ToString(Motion motion);
// Accepts the names above, with '_' for '-' too. nullopt if unknown.
std::optional<Motion> ParseMotion(const std::string& text);

// "linear", "sidewind", "roll".
const char* ToString(GaitKind kind);
std::optional<GaitKind> ParseGaitKind(const std::string& text);

}  // namespace mrsim

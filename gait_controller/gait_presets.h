// The built-in gaits: the presets measured on an 11-module robot in the
// original (domain.md section 4), with the pitch-to-yaw lag this project
// adds for the sidewinding ones, plus a sidewinding gait tuned for MuJoCo
// (docs/gait.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gait_controller/gait.h"

namespace mrsim {

// forward, forward-strong, turn-wide, turn-sharp, sidewind-1, sidewind-2,
// rolling (the domain's table, in that order), then sidewind (tuned here),
// the classic gaits serpenoid, concertina, helical-pole, helical-pipe,
// conical-sidewind, and the CPG gaits cpg-forward and cpg-serpenoid.
const std::vector<Gait>& GaitPresets();
// The preset with this name ('_' accepted for '-'), or nullopt.
std::optional<Gait> FindGaitPreset(const std::string& name);
// "forward, forward-strong, ..." for error messages and --help.
std::string GaitPresetNames();

}  // namespace mrsim

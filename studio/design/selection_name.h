// A selection named in words, for `mrsim-studio --select NAME`: a robot
// or object by its name, a part of a robot by its kind and place, so a
// screenshot can show the selection glow and the move and turn handles.
#pragma once

#include <string>

#include "sim_core/scenario/scenario.h"
#include "studio/design/selection.h"

namespace mrsim::studio {

// NAME is a robot's name, a scene object's guid, "[ROBOT ]module N",
// "[ROBOT ]sensor_module N" or "[ROBOT ]lock N" (N counted from 0 in the
// robot's list; the first robot when none is named), "loose_frame N",
// "loose_joint N", "loose_sensor_module N", "terrain", "settings" or
// "none". Throws
// DesignError saying what names the scenario has.
Selection SelectionNamed(const Scenario& scenario, const std::string& name);

}  // namespace mrsim::studio

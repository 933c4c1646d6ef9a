// A design's saved run settings (Scenario::run, <run> in the file) and
// the Run form's RunOptions, each made from the other: Save writes the
// form into the design, opening a design fills the form, so Run after
// opening does what the author saw.
#pragma once

#include <optional>
#include <string>

#include "sim_core/scenario/run_settings.h"
#include "studio/live/live_runner.h"

namespace mrsim::studio {

// The form from saved settings is RunOptionsFromSettings
// (launcher/run_options.h, shared with `mrsim run`); the controller panel
// takes run->lua_script itself.

// What Save writes for the form `o`, the Lua source in the editor and the
// gait tuned in the Run panel (a gait file's text, "" when none). The
// script is kept only when the controller is Lua, the tuned gait only
// when it is the gait.
RunSettings SettingsFromRunOptions(const RunOptions& o,
                                   const std::string& lua_source,
                                   const std::string& tuned_gait = "");

}  // namespace mrsim::studio

// A design's saved optimisation setup (Scenario::optimization,
// <optimization> in the file) and the Optimise form's OptimiseOptions, each
// made from the other: Save writes the form into the design, opening a
// design fills the form, so Start optimisation after opening runs what the
// author set up, and `mrsim-opt FILE` runs the same.
#pragma once

#include <string>

#include "sim_core/scenario/optimization_settings.h"
#include "studio/live/optimise_session.h"

namespace mrsim::studio {

// What Save writes for the form `o`: its genome written out (a gait's),
// the algorithm's settings as flag=value words. The Lua controller is
// "lua", the design's own <run> script.
OptimizationSettings SavedOptimisation(const OptimiseOptions& o);

// The form's options from saved settings, on top of `o` (what the file
// does not hold: folder, farm, URLs, the Lua source). Throws
// std::invalid_argument naming the field that no form can show (an
// unknown algorithm or distance, a genome that does not read).
OptimiseOptions OptionsFromSaved(const OptimizationSettings& s,
                                 OptimiseOptions o);

}  // namespace mrsim::studio

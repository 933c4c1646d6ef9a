// A scenario whose physics explodes within a few steps: a light, stiff
// chain with a far too large timestep.
#pragma once

#include "sim_core/scenario/scenario.h"

namespace mrsim::testing {

Scenario ExplodingScenario();

}  // namespace mrsim::testing

// The simulator's clock: the enum and its words live in common/ (a
// scenario's saved run settings use them too, and sim_core has no LCM);
// this header keeps the runtime's include path.
#pragma once

#include "common/clock_mode.h"

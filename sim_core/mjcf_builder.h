// Turns a Scenario into MuJoCo MJCF text. The output is self-contained apart
// from mesh and height-field files, which it names by absolute path, so it
// opens in mujoco-simulate / mujoco-testxml.
#pragma once

#include <string>

#include "sim_core/scenario.h"

namespace mrsim {

std::string BuildMjcf(const Scenario& scenario);

}  // namespace mrsim

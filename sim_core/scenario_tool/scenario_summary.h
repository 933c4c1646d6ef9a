// A human-readable summary of a scenario for `mrsim-scenario info`.
#pragma once

#include <string>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Total mass of a robot's parts (frames, sensor modules and sensors), kg.
double RobotMass(const Robot& robot);

// Several lines: robots (modules, joints, sensors, mass), scene objects,
// terrain, materials, fluid regions, settings. Reads the terrain image to
// report its size.
std::string SummarizeScenario(const Scenario& scenario);

// "1 module", "3 modules".
std::string Counted(size_t n, const char* what);

}  // namespace mrsim

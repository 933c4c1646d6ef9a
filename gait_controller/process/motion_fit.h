// Whether a motion can act on a robot's joints: turning is a yaw offset, so
// a robot without yaw joints cannot turn; the linear wave needs pitch
// joints; sidewinding and rolling need both.
#pragma once

#include <string>
#include <vector>

#include "gait_controller/motion.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Empty when `motion` can act on a chain with these hinge axes, otherwise
// one line saying why not and what would.
std::string MotionFitWarning(Motion motion, const std::vector<Axis>& axes);

}  // namespace mrsim

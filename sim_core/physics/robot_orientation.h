// The whole robot's orientation as the state reports it (docs/sim.md, "The
// robot's orientation"): one definition shared by the physics, which fills
// it, and by tests and tools that need the heading of a pose.
#pragma once

#include <Eigen/Geometry>

#include "sim_core/scenario/robot_state.h"

namespace mrsim {

// Yaw of the frame's forward (+x) axis about world z, in rad (-pi..pi): 0
// facing +x, pi/2 facing +y. 0 when that axis points straight up or down,
// where no heading is defined.
double HeadingOf(const Eigen::Quaterniond& orientation);

// Sets state->orientation and state->heading from the head frame
// (state->frames[0], module 0's front frame), or from the first sensor
// module when the robot has no modules; identity and 0 when it has neither.
void FillRobotOrientation(RobotState* state);

}  // namespace mrsim

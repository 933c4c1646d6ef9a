// Pure conversions between the physics' RobotState and the LCM message
// robot_state_t, so every process (sim, controllers, tests) encodes a state
// the same way and nothing but main touches lcm::LCM.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/physics/scene_object_state.h"

namespace mrsim {

// Simulation time (s) as message utime (us), rounded to the nearest us.
int64_t SimTimeToUtime(double seconds);

// The message for one robot's state; seq is the publication counter.
robot_state_t ToRobotStateMessage(const RobotState& state, int64_t seq);

// Fills the message's lock list (Physics::LockStates: names in scenario
// order and whether each holds).
void SetLockStates(const std::vector<std::pair<std::string, bool>>& locks,
                   robot_state_t* msg);

// The inverse (time from sim_time); lossless for everything the message
// holds.
RobotState FromRobotStateMessage(const robot_state_t& msg);

// The message for the movable scene objects at simulation time `time` (s);
// seq is that of the robot states of the same control period.
scene_state_t ToSceneStateMessage(const std::vector<SceneObjectState>& objects,
                                  double time, int64_t seq);

// The inverse. Throws std::invalid_argument when num_objects disagrees with
// the arrays (a message built by hand; decode() enforces it otherwise).
std::vector<SceneObjectState> FromSceneStateMessage(const scene_state_t& msg);

}  // namespace mrsim

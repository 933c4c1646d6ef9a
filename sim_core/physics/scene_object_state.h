// The world poses of a simulation's movable scene objects, read from the
// physics so they can be published and drawn where they really are.
#pragma once

#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/robot_state.h"

namespace mrsim {

// One scene object: `index` is its position in Scenario::scene_objects.
struct SceneObjectState {
  int index = 0;
  Pose pose;  // body frame in the world
};

// Every non-static scene object, in scenario order, from the body
// mjcf_names::SceneObject(i) of the last step. Empty when there are none.
// Throws std::runtime_error when a movable object has no body.
std::vector<SceneObjectState> ReadSceneObjects(const Physics& physics);

}  // namespace mrsim

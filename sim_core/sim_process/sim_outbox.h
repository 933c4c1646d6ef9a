// What the simulator's node publishes: states, scene states and statuses.
#pragma once

#include "lcmtypes/runtime/outbox.h"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"
#include "mrsim/sim_status_t.hpp"

namespace mrsim {

using SimOutbox = Outbox<robot_state_t, scene_state_t, sim_status_t>;

}  // namespace mrsim

// The distance rays of the live view: each sensor's ray from its site,
// along its direction, as long as the distance the running simulation
// measured (the designed maximum when nothing is within range, as the
// simulator reports a miss), so an obstacle ends the ray where it is.
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "sim_core/scenario/robot_state.h"
#include "viewer/renderer.h"
#include "viewer/state_pose_mapper.h"

namespace mrsim::studio {

// The rays of every robot with a state (`states[r]` null: none for robot
// r), in the pose of the mapper's last Apply on `data`.
std::vector<Ray> MeasuredRays(const StatePoseMapper& mapper,
                              const std::vector<const RobotState*>& states,
                              const mjData* data);

// The ray of the distance sensor at `site` in the pose of `data` (after
// mj_kinematics), as the simulator casts it: from the site along its x
// axis, skipping the sensor module and its force plate, to the first thing
// within `length`. The design view draws these.
Ray CastSiteRay(const mjModel* m, const mjData* d, int site, double length);

}  // namespace mrsim::studio

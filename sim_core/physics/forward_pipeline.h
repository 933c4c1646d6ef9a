// MuJoCo's forward pipeline run stage by stage, so contacts can be changed
// between collision detection and constraint building (directional
// friction). With nothing to change it is exactly mj_step1 / mj_forward,
// bit for bit (PhysicsDirectionalFriction.StagedPipelineMatchesMuJoCo).
#pragma once

#include <mujoco/mujoco.h>

#include "sim_core/physics/directional_friction.h"

namespace mrsim {

// mj_fwdPosition with `friction` applied after mj_collision (nullptr or
// empty: mj_fwdPosition itself).
void ForwardPosition(const mjModel* m, mjData* d,
                     const DirectionalFriction* friction);

// mj_step1 (checks, position and velocity stages, sensors, energy).
void Step1(const mjModel* m, mjData* d, const DirectionalFriction* friction);

// mj_forward.
void Forward(const mjModel* m, mjData* d, const DirectionalFriction* friction);

}  // namespace mrsim

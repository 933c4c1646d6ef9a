// MuJoCo's forward pipeline run stage by stage, so the physics effects that
// rewrite contacts (PhysicsEffect::AdjustContacts: directional friction)
// run between collision detection and constraint building. With no such
// effect it is exactly mj_step1 / mj_forward, bit for bit
// (PhysicsDirectionalFriction.StagedPipelineMatchesMuJoCo).
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "sim_core/physics/physics_effect.h"

namespace mrsim {

// The effects whose contact hook runs, in table order
// (PhysicsEffects::contacts()).
using ContactEffects = std::vector<const PhysicsEffect*>;

// mj_fwdPosition with each of `contacts` adjusting the contacts after
// mj_collision (none: mj_fwdPosition itself).
void ForwardPosition(const mjModel* m, mjData* d,
                     const ContactEffects& contacts);

// mj_step1 (checks, position and velocity stages, sensors, energy).
void Step1(const mjModel* m, mjData* d, const ContactEffects& contacts);

// mj_forward.
void Forward(const mjModel* m, mjData* d, const ContactEffects& contacts);

}  // namespace mrsim

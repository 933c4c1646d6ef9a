#include "sim_core/physics/forward_pipeline.h"

namespace mrsim {

void ForwardPosition(const mjModel* m, mjData* d,
                     const ContactEffects& contacts) {
  if (contacts.empty()) {
    mj_fwdPosition(m, d);
    return;
  }
  // The stages of MuJoCo 2.2's mj_fwdPosition (engine_forward.c), in its
  // order, with the contacts rewritten before the constraints are made
  // from them. Only the stage timers (mjData::timer) are not recorded.
  mj_kinematics(m, d);
  mj_comPos(m, d);
  mj_camlight(m, d);
  mj_tendon(m, d);
  mj_crb(m, d);
  mj_factorM(m, d);
  mj_collision(m, d);
  for (const PhysicsEffect* effect : contacts) effect->AdjustContacts(m, d);
  mj_makeConstraint(m, d);
  mj_transmission(m, d);
  mj_projectConstraint(m, d);
}

void Step1(const mjModel* m, mjData* d, const ContactEffects& contacts) {
  if (contacts.empty()) {
    mj_step1(m, d);
    return;
  }
  mj_checkPos(m, d);
  mj_checkVel(m, d);
  ForwardPosition(m, d, contacts);
  mj_sensorPos(m, d);
  if (m->opt.enableflags & mjENBL_ENERGY) mj_energyPos(m, d);
  mj_fwdVelocity(m, d);
  mj_sensorVel(m, d);
  if (m->opt.enableflags & mjENBL_ENERGY) mj_energyVel(m, d);
  if (mjcb_control) mjcb_control(m, d);
}

void Forward(const mjModel* m, mjData* d, const ContactEffects& contacts) {
  if (contacts.empty()) {
    mj_forward(m, d);
    return;
  }
  ForwardPosition(m, d, contacts);
  mj_sensorPos(m, d);
  if (m->opt.enableflags & mjENBL_ENERGY) mj_energyPos(m, d);
  mj_forwardSkip(m, d, mjSTAGE_POS, 0);
}

}  // namespace mrsim

// Is a fast optimised gait physics or an artefact of the step? The gait
// CMA-ES finds for scenarios/snake11.xml (mrsim-opt --algorithm cmaes
// --population 8 --generations 10 --episode 5 --no-start-genome --seed 2)
// tumbles end over end at about 0.9 m/s. A gait that lives on a numerical
// artefact (contacts that pop out, servos that chatter at the step rate,
// energy from nowhere) changes when the timestep is halved and breaks the
// energy balance; these tests hold the real one to both
// (docs/physics.md, "Is a fast gait real?").
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "gait_controller/gait_controller.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_runner.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

constexpr double kEpisode = 5.0;  // s, the bench's CMA-ES episodes
constexpr double kControlPeriod = 0.01;
constexpr double kBodyLength = 1.1;  // m: 11 modules of two 5 cm frames

// The CMA-ES optimum (A_pitch and offset at their upper limits, T at its
// lower limit): the body curls, stands on one end and tumbles forwards.
Gait TumblingGait() {
  Gait gait = *FindGaitPreset("forward");
  gait.name = "tumbling";
  gait.parameters.amplitude_pitch = 1.57;
  gait.parameters.phase_pitch = 0.6123814956571902;
  gait.parameters.period = 1.0;
  gait.parameters.offset_pitch = 0.3;
  return gait;
}

Scenario Snake11(double timestep) {
  Scenario s = ReadScenarioFile(testing::SourcePath("scenarios/snake11.xml"));
  s.settings.timestep = timestep;
  return s;
}

struct Travel {
  double distance = 0;  // m, CoM along +x (the optimiser's fitness)
  double energy = 0;    // J, sum of |torque * speed| dt (its energy term)
};

Travel RunTumbling(double timestep) {
  Physics physics(Snake11(timestep));
  GaitController controller(JointAxes(physics, 0));
  controller.SetGait(TumblingGait());
  const GaitRunResult r =
      RunGait(physics, 0, controller, kEpisode, kControlPeriod);
  return {r.com_end.x() - r.com_start.x(), r.energy};
}

TEST(PhysicsConvergence, TumblingGaitTravelsTheSameAtHalfTheTimestep) {
  const Travel coarse = RunTumbling(0.002);  // the scenario's step
  const Travel fine = RunTumbling(0.001);
  // It is a gait worth checking: several body lengths in 5 s.
  EXPECT_GT(coarse.distance, 2 * kBodyLength);
  // Measured 4.342 m and 4.340 m (4.366 m at 0.5 ms).
  EXPECT_NEAR(fine.distance, coarse.distance, 0.05 * coarse.distance);
  // Servos that chatter at the step rate (velocity gain x step over the
  // joint's inertia above 1) would still tumble but use several times the
  // energy at 2 ms: measured 59.3 J and 57.9 J.
  EXPECT_NEAR(fine.energy, coarse.energy, 0.1 * coarse.energy);
}

// Mechanical energy of the whole model: kinetic (armature included) plus
// potential in gravity.
double MechanicalEnergy(const mjModel* m, const mjData* d) {
  std::vector<mjtNum> mv(m->nv);
  mj_mulM(m, d, mv.data(), d->qvel);
  double e = 0;
  for (int i = 0; i < m->nv; ++i) e += 0.5 * d->qvel[i] * mv[i];
  for (int b = 1; b < m->nbody; ++b) {
    for (int k = 0; k < 3; ++k) {
      e -= m->body_mass[b] * m->opt.gravity[k] * d->xipos[3 * b + k];
    }
  }
  return e;
}

TEST(PhysicsConvergence, TumblingGaitGetsItsEnergyFromTheServosOnly) {
  Physics physics(Snake11(0.002));
  const mjModel* m = physics.model();
  const mjData* d = physics.data();
  GaitController controller(JointAxes(physics, 0));
  controller.SetGait(TumblingGait());
  const int steps =
      static_cast<int>(std::lround(kControlPeriod / physics.timestep()));
  const int periods = static_cast<int>(std::lround(kEpisode / kControlPeriod));
  const double e0 = MechanicalEnergy(m, d);
  const double dt = physics.timestep();
  double servo_work = 0, servo_positive_work = 0, constraint_work = 0;
  double last = physics.time();
  std::vector<mjtNum> v0(m->nv);
  for (int k = 0; k < periods; ++k) {
    const double now = physics.time();
    physics.SetJointTargets(0, controller.Update(k == 0 ? 0.0 : now - last));
    last = now;
    for (int i = 0; i < steps; ++i) {
      std::copy(d->qvel, d->qvel + m->nv, v0.begin());
      physics.Step();
      // Work at the step's mean velocity: for the semi-implicit Euler step
      // the change of kinetic energy is exactly force . (v0 + v1) / 2 dt.
      for (int a = 0; a < m->nu; ++a) {
        const int dof = m->jnt_dofadr[m->actuator_trnid[2 * a]];
        const double w =
            d->actuator_force[a] * 0.5 * (v0[dof] + d->qvel[dof]) * dt;
        servo_work += w;
        servo_positive_work += std::max(0.0, w);
      }
      for (int v = 0; v < m->nv; ++v) {
        constraint_work +=
            d->qfrc_constraint[v] * 0.5 * (v0[v] + d->qvel[v]) * dt;
      }
    }
  }
  const double gained = MechanicalEnergy(m, d) - e0;
  ASSERT_GT(servo_positive_work, 10.0);  // J: the servos did drive it
  // Contacts and joint limits take energy out (impacts, friction); they
  // never put any in. Measured: -11 J of 42 J the servos put in.
  EXPECT_LT(constraint_work, 0.0);
  // What the body gained is what servos and constraints did, up to the
  // integrator's own error (measured 0.2 J).
  EXPECT_NEAR(gained, servo_work + constraint_work, 0.02 * servo_positive_work);
}

}  // namespace
}  // namespace mrsim

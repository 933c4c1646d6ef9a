// What a physics effect is: something Physics adds to MuJoCo's own model at
// fixed points of each step (fluid drag and buoyancy, directional friction,
// the reality gap's servo and sensor imperfections). Each effect is one
// class behind this interface, listed once in PhysicsEffectKinds()
// (physics_effect_kinds.h); Physics builds the effects a scenario needs
// from that list and calls them at their hooks, as MuJoCo's mj_passive
// sums its named contributors (docs/physics.md, "Physics effects").
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <vector>

#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

struct RealityGap;

// The points of a step where an effect takes part. An effect's row in
// PhysicsEffectKinds() says which of them it uses; Physics calls only
// those, and a hook no built effect uses costs one empty-list test.
enum PhysicsHook : unsigned {
  // Before the dynamics: the servos' commands (mjData::ctrl).
  kHookControls = 1u << 0,
  // Before the dynamics: the forces on bodies (mjData::xfrc_applied).
  kHookBodyForces = 1u << 1,
  // Between collision detection and constraint building: the contacts.
  kHookContacts = 1u << 2,
  // After reading a robot's state back: its readings.
  kHookReadings = 1u << 3,
};

// One hinge's servo: where its angle and command live, and its law.
struct HingeServo {
  int joint = -1;
  int qpos = 0;
  int dof = 0;
  int actuator = -1;
  int module = 0;
  Axis axis = Axis::kPitch;
  double kp = 0, max_vel = 0, lower = 0, upper = 0;
};

// A robot's servos and the targets they were last given: what a control
// effect drives.
struct ServoRobot {
  uint64_t id = 0;  // the robot's index in the whole scenario (noise keys)
  std::vector<HingeServo> servos;
  std::vector<double> targets;  // rad, one per servo, within its limits
};

// What an effect is made from: the scenario, the model compiled from it
// (for a world of a split scene: that world's part and model) and the
// reality gap Physics::SetRealityGap set (off by default).
struct PhysicsEffectInput {
  const Scenario& scenario;
  const mjModel* model;
  const RealityGap& gap;
};

class PhysicsEffect {
 public:
  virtual ~PhysicsEffect() = default;

  // kHookBodyForces: adds this effect's forces on bodies for the next step
  // of state `d` (kinematics current) into `xfrc` (nbody x 6, world frame,
  // force then torque). Physics zeroes xfrc before the first such effect:
  // while one is built, the body-force effects own mjData::xfrc_applied.
  virtual void AddBodyForces(const mjModel* /*m*/, const mjData* /*d*/,
                             mjtNum* /*xfrc*/) const {}

  // kHookContacts: rewrites d->contact after mj_collision, before
  // mj_makeConstraint (the kinematics are current). With no such effect
  // the forward pipeline is MuJoCo's own mj_step1 / mj_forward.
  virtual void AdjustContacts(const mjModel* /*m*/, mjData* /*d*/) const {}

  // kHookControls: writes d->ctrl of every servo in place of the nominal
  // servo law. `advance` is false for the force readings' private forward
  // of the current state (d->ctrl then holds the last step's commands).
  // At most one effect of the table takes this hook.
  virtual void Controls(const mjModel* /*m*/,
                        const std::vector<const ServoRobot*>& /*robots*/,
                        mjData* /*d*/, bool /*advance*/) {}

  // kHookReadings: changes robot `robot`'s state as read at step `step`
  // (robot: its index in the whole scenario; max_distance: per sensor
  // module, each distance sensor's range).
  virtual void AdjustReadings(
      uint64_t /*step*/, uint64_t /*robot*/,
      const std::vector<std::vector<double>>& /*max_distance*/,
      RobotState* /*state*/) const {}

  // Starts the effect's own history (e.g. a latency queue) from the
  // robots' current targets: after it is built and at Physics::Reset().
  virtual void Restart(const std::vector<const ServoRobot*>& /*robots*/) {}

  // A world of a split scene that took over the robots of another world
  // takes that world's history: robot r of `from` is robot to_robot[r]
  // here (-1: not here). `from` is the same effect (same table row).
  virtual void Absorb(const PhysicsEffect& /*from*/,
                      const std::vector<int>& /*to_robot*/) {}
};

}  // namespace mrsim

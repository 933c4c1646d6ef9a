// The MuJoCo world built from a Scenario: owns mjModel/mjData, servos the
// hinges with the P-on-speed law and reads every part back as RobotState.
#pragma once

#include <mujoco/mujoco.h>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim_core/mujoco/mujoco_ptr.h"
#include "sim_core/mujoco/physics_error.h"
#include "sim_core/physics/reality_gap.h"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

class Physics {
 public:
  // Builds the MJCF in memory and compiles it. Throws std::runtime_error
  // naming the part that failed (e.g. an unreadable mesh).
  explicit Physics(const Scenario& scenario);
  ~Physics();
  Physics(const Physics&) = delete;
  Physics& operator=(const Physics&) = delete;

  // Advances one timestep; throws PhysicsError on instability.
  void Step();
  // Advances n timesteps.
  void Step(int n);
  // Back to the initial state of the scenario; joint targets back to zero.
  void Reset();

  double time() const;
  double timestep() const;

  // Robots, joints and sensor modules are indexed in scenario order; an
  // index out of range throws std::out_of_range.
  int robot_count() const;
  const std::string& robot_name(int robot) const;
  // Index of the robot with this name, or -1.
  int robot_index(const std::string& name) const;
  // Hinge joints of a robot, in chain order.
  int joint_count(int robot) const;
  Axis joint_axis(int robot, int joint) const;
  double joint_lower_limit(int robot, int joint) const;
  double joint_upper_limit(int robot, int joint) const;
  // Index of the module a hinge belongs to (modules with a Lock joint have
  // no hinge, so joint and module indices may differ).
  int joint_module(int robot, int joint) const;
  int module_count(int robot) const;
  int sensor_module_count(int robot) const;

  // Releases (attached=false) or re-makes (true) the lock named `lock` (its
  // guid, or its generated name) of robot `robot`. Throws PhysicsError
  // naming the robot/lock when there is no such lock. A re-made lock pulls
  // its parts back to their relative pose in the scenario.
  void SetLockAttached(const std::string& robot, const std::string& lock,
                       bool attached);
  // Names and attached state of every lock of `robot`, in scenario order;
  // kLooseOwnerName gives the loose parts' locks (a broken one detached).
  // Throws PhysicsError naming the robot when there is no such robot.
  std::vector<std::pair<std::string, bool>> LockStates(
      const std::string& robot) const;

  // Targets (rad) for every hinge of a robot; clamped to the joint limits.
  // Throws std::invalid_argument on a wrong count or a non-finite value.
  void SetJointTargets(int robot, const std::vector<double>& targets);
  const std::vector<double>& joint_targets(int robot) const;

  // The loose hinges that have a servo (Joint::servo), in the order
  // ReadLooseState lists the loose hinges, skipping the passive ones; 0
  // without. Targets for them as SetJointTargets takes a robot's: one per
  // loose servo, clamped to its limits; throws std::invalid_argument on a
  // wrong count or a non-finite value. The reality gap does not act on
  // them (it is a robot's servos'); checkpoints keep their targets.
  int loose_servo_count() const;
  void SetLooseTargets(const std::vector<double>& targets);
  const std::vector<double>& loose_targets() const;

  // Everything about one robot at the current time. Poses and velocities
  // are those of the current state (kinematics are kept up to date after
  // every step); force sensors need a constraint solve and distance sensors
  // ray casts, so they are computed here, never in Step(). Uses a private
  // scratch mjData: do not call it on one Physics from two threads at once.
  RobotState ReadRobotState(int robot) const;
  // Whether the scenario has loose frames or sensor modules (Scenario::
  // loose_*), and their state as ReadRobotState gives a robot's, under the
  // owner name kLooseOwnerName: `frames` one pose per loose frame in
  // scenario order (no `modules`), `joints` the loose hinges in scenario
  // order (a passive one's torque 0), `sensor_modules` the loose sensor modules
  // with their readings (no reality-gap noise), `com` theirs together.
  // ReadLooseState throws std::logic_error when there are none.
  bool has_loose_parts() const;
  RobotState ReadLooseState() const;

  // Per-step imperfections of servos and sensors from now on (motor noise,
  // latency, backlash, acceleration limit, sensor noise and bias; the
  // per-episode parts are PerturbScenario's). Reset() keeps it; a default
  // RealityGap turns it off. Throws std::invalid_argument as Validate.
  void SetRealityGap(const RealityGap& gap);
  // The physics effects this scene runs, by their names in
  // PhysicsEffectKinds() (physics_effect_kinds.h) and in its order: those
  // its scenario and reality gap give something to do ("fluids",
  // "directional_friction", "reality_gap"); the others cost nothing.
  std::vector<std::string> effects() const;
  Eigen::Vector3d CenterOfMass(int robot) const;

  // The full physics state (lock states, time, qpos and qpos before the
  // kinematics renormalised it, qvel, act, ctrl, warm start, applied
  // forces, actuator forces, sensordata, targets) as bytes; LoadState
  // restores it so stepping and ReadRobotState continue bit for bit
  // (rebuilding the model first if the saved run released a lock the
  // model held rigidly). LoadState throws std::invalid_argument for bytes
  // saved from another scenario. Format: docs/physics.md.
  std::vector<unsigned char> SaveState() const;
  void LoadState(const std::vector<unsigned char>& bytes);

  const Scenario& scenario() const;
  const mjModel* model() const;
  const mjData* data() const;
  // For tests and tools that poke the state (e.g. apply a push through
  // xfrc_applied; note Physics overwrites xfrc_applied when the scenario
  // has fluid regions).
  mjData* mutable_data();

 private:
  // Scenes whose robots cannot touch run as several MuJoCo worlds
  // (world_split.h); each world is a Physics of its own, built here.
  friend class WorldSplit;
  // One world of a split scene: `part` holds the robots `global_ids` of
  // the whole scenario (noise and sensor keys use those indices) and the
  // scene objects not in `skip_objects`.
  Physics(const Scenario& part, std::vector<int> global_ids,
          std::vector<bool> skip_objects);
  // Takes the state of `parts` (worlds whose robots this freshly built
  // world holds) by name: positions, speeds, warm start, forces, controls,
  // locks, targets and the reality gap's history.
  void AbsorbState(const std::vector<const Physics*>& parts);
  // Distance rays also see what this function returns (the other worlds):
  // arguments are the ray's origin, its site's xmat and its range.
  using RayCast =
      std::function<double(const double* point, const double* xmat, double)>;
  void SetOtherWorldsRay(RayCast cast);
  // Recomputes the current state after qpos or qvel were written directly.
  void AfterPoke();

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrsim

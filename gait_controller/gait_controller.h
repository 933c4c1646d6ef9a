// Turns motion commands and gait parameters into joint targets for one
// chain, deterministically from the commands and the time steps given. No
// target ever jumps: the phase is integrated (never recomputed from t) and
// amplitudes, offsets, per-joint phase shifts and the phase speed ramp at
// fixed rates, with a hard bound on each target's rate of change.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "gait_controller/gait.h"
#include "gait_controller/gait_parameters.h"
#include "gait_controller/motion.h"
#include "sim_core/scenario.h"

namespace mrsim {

struct GaitControllerOptions {
  // Hard bound on every target's change per second (rad/s). Above the
  // default servo max_vel (3 rad/s) and the fastest preset wave (A_p = 2,
  // T = 4 s: pi rad/s), so it only bites on switches.
  double max_target_rate = 4.0;
  double shape_rate = 1.0;  // rad/s: amplitude and offset ramps
  double shift_rate = 3.14159265358979323846;  // rad/s: per-joint phase shift
  double drive_rate = 2.0;  // 1/s: ramp of the signed phase-speed factor
  // Yaw offset (rad) at turn strength 1 (the size of turn-sharp's offset;
  // turning left is a negative yaw offset on MakeChain robots).
  double max_turn_offset = 0.8;
  // |target| never exceeds this (mrsim-sim rejects targets beyond pi).
  double target_limit = 3.14159265358979323846;
};

class GaitController {
 public:
  // joint_axes: the robot's hinge axes in chain order (Physics::joint_axis).
  // Starts at rest (targets 0), running the forward preset, motion forward:
  // amplitudes ramp in from zero. Throws std::invalid_argument on an empty
  // chain or bad options.
  explicit GaitController(std::vector<Axis> joint_axes,
                          GaitControllerOptions options = {});

  // Replaces the gait of gait.kind and runs it: the motion becomes forward,
  // sidewind-left or roll (strength 1) unless the current motion already
  // uses that kind. Throws std::invalid_argument on bad parameters (nothing
  // changes then).
  void SetGait(const Gait& gait);
  // Replaces the parameters of the gait the current motion uses (its name
  // becomes "custom"). Throws std::invalid_argument on bad parameters.
  void SetParameters(const GaitParameters& parameters);
  // strength in [-1, 1]: for forward, backward, sidewind and roll the speed
  // of the phase (negative reverses); for the turns the fraction of
  // max_turn_offset (negative turns the other way). Ignored by stop.
  // Throws std::invalid_argument when strength is out of range or NaN.
  void SetMotion(Motion motion, double strength = 1.0);
  // Direction inputs, each in [-1, 1] (a joystick). Linear gait: forward is
  // the phase speed (negative: backward), turn the yaw offset (positive:
  // left). Sidewind and roll: turn sets the direction and speed (positive:
  // left), forward is ignored. Leaves stop. Throws std::invalid_argument.
  void SetDirection(double forward, double turn);

  // Advances by dt seconds (>= 0) and returns the new targets (rad, chain
  // order). Throws std::invalid_argument on a negative or non-finite dt.
  const std::vector<double>& Update(double dt);
  // Back to rest (targets 0, phase 0, time 0); gaits and motion are kept.
  void Reset();

  // Everything that evolves (gaits, motion, ramps, phase, time) as text,
  // doubles exact (hex floats), so a controller restored with LoadState
  // continues bit for bit (mrsim-gait saves it beside a checkpoint).
  std::string SaveState() const;
  // Restores what SaveState wrote. Throws std::invalid_argument on text
  // that is not such a state or is for another joint count (nothing
  // changes then).
  void LoadState(const std::string& text);

  Motion motion() const { return motion_; }
  double strength() const { return strength_; }
  bool stopped() const { return stopped_; }
  GaitKind active_kind() const { return kind_; }
  // The gait the current motion uses (when stopped: the one it stopped).
  const Gait& active_gait() const;
  const Gait& gait(GaitKind kind) const;
  const std::vector<double>& targets() const { return targets_; }
  double time() const { return time_; }
  double phase() const { return phase_; }
  double drive() const { return drive_; }
  int joint_count() const { return static_cast<int>(axes_.size()); }
  const std::vector<Axis>& joint_axes() const { return axes_; }
  const GaitControllerOptions& options() const { return options_; }
  // The waves the ramps are heading for (for tests and displays).
  const std::vector<JointWave>& goal_waves() const { return goal_; }
  // True when every ramp has reached its goal.
  bool settled() const;

 private:
  void Recompute();

  std::vector<Axis> axes_;
  GaitControllerOptions options_;
  std::array<Gait, 3> gaits_;
  GaitKind kind_ = GaitKind::kLinear;
  Motion motion_ = Motion::kForward;
  double strength_ = 1.0;
  bool stopped_ = false;
  double drive_goal_ = 1.0;  // signed phase-speed factor
  double turn_ = 0.0;        // linear gait: fraction of max_turn_offset

  std::vector<JointWave> goal_;
  std::vector<JointWave> waves_;  // ramped
  std::vector<double> targets_;
  double drive_ = 0.0;
  double phase_ = 0.0;
  double time_ = 0.0;
};

}  // namespace mrsim

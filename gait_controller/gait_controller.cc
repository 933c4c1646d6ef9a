#include "gait_controller/gait_controller.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gait_controller/gait_presets.h"

namespace mrsim {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;

// Sign conventions (docs/gait.md), measured on MakeChain robots: a positive
// phase speed makes the pitch wave travel so the robot moves toward module
// 0 (+x); a negative yaw offset bends the chain so it turns left
// (counter-clockwise seen from above); a positive phase speed sidewinds
// (sidewind preset) and rolls (rolling preset) to the left of the heading.
constexpr double kForwardDrive = 1.0;
constexpr double kLeftTurn = -1.0;
constexpr double kSidewindLeftDrive = 1.0;
constexpr double kRollDrive = 1.0;

int KindIndex(GaitKind kind) { return static_cast<int>(kind); }

double Approach(double value, double goal, double max_step) {
  const double d = goal - value;
  if (std::abs(d) <= max_step) return goal;
  return value + (d > 0 ? max_step : -max_step);
}

// Like Approach, but for an angle: heads the short way round and lands on
// the goal exactly.
double ApproachAngle(double value, double goal, double max_step) {
  const double d = std::remainder(goal - value, kTwoPi);
  if (std::abs(d) <= max_step) return goal;
  return value + (d > 0 ? max_step : -max_step);
}

void CheckInput(const char* what, double v) {
  if (!std::isfinite(v) || v < -1.0 || v > 1.0) {
    throw std::invalid_argument(
        fmt::format("gait controller: {} must be in [-1, 1], got {}", what, v));
  }
}

}  // namespace

GaitController::GaitController(std::vector<Axis> joint_axes,
                               GaitControllerOptions options)
    : axes_(std::move(joint_axes)),
      options_(options),
      cpg_(std::max<int>(1, static_cast<int>(axes_.size()))) {
  if (axes_.empty()) {
    throw std::invalid_argument("gait controller: the chain has no joints");
  }
  const double positives[] = {options_.max_target_rate, options_.shape_rate,
                              options_.shift_rate, options_.drive_rate,
                              options_.target_limit};
  for (double v : positives) {
    if (!std::isfinite(v) || v <= 0) {
      throw std::invalid_argument(
          "gait controller: rates and target_limit must be positive");
    }
  }
  if (!std::isfinite(options_.max_turn_offset)) {
    throw std::invalid_argument("gait controller: max_turn_offset not finite");
  }
  gaits_[KindIndex(GaitKind::kLinear)] = *FindGaitPreset("forward");
  gaits_[KindIndex(GaitKind::kSidewind)] = *FindGaitPreset("sidewind");
  gaits_[KindIndex(GaitKind::kRoll)] = *FindGaitPreset("rolling");
  drive_goal_ = kForwardDrive;
  feedback_.assign(axes_.size(), 0.0);
  Reset();
}

const Gait& GaitController::active_gait() const {
  return gaits_[KindIndex(kind_)];
}

const Gait& GaitController::gait(GaitKind kind) const {
  return gaits_[KindIndex(kind)];
}

void GaitController::SetGait(const Gait& gait) {
  ValidateGaitParameters(gait.parameters, joint_count());
  if (gait.cpg) ValidateCpgParameters(*gait.cpg);
  gaits_[KindIndex(gait.kind)] = gait;
  if (stopped_ || kind_ != gait.kind) {
    switch (gait.kind) {
      case GaitKind::kLinear:
        SetMotion(Motion::kForward);
        return;
      case GaitKind::kSidewind:
        SetMotion(Motion::kSidewindLeft);
        return;
      case GaitKind::kRoll:
        SetMotion(Motion::kRoll);
        return;
    }
  }
  Recompute();
}

void GaitController::SetParameters(const GaitParameters& parameters) {
  ValidateGaitParameters(parameters, joint_count());
  Gait& g = gaits_[KindIndex(kind_)];
  g.parameters = parameters;
  g.name = "custom";
  Recompute();
}

void GaitController::SetMotion(Motion motion, double strength) {
  CheckInput("strength", strength);
  motion_ = motion;
  strength_ = strength;
  stopped_ = false;
  switch (motion) {
    case Motion::kForward:
      kind_ = GaitKind::kLinear;
      drive_goal_ = strength * kForwardDrive;
      turn_ = 0;
      break;
    case Motion::kBackward:
      kind_ = GaitKind::kLinear;
      drive_goal_ = -strength * kForwardDrive;
      turn_ = 0;
      break;
    case Motion::kTurnLeft:
      kind_ = GaitKind::kLinear;
      drive_goal_ = kForwardDrive;
      turn_ = strength;
      break;
    case Motion::kTurnRight:
      kind_ = GaitKind::kLinear;
      drive_goal_ = kForwardDrive;
      turn_ = -strength;
      break;
    case Motion::kSidewindLeft:
      kind_ = GaitKind::kSidewind;
      drive_goal_ = strength * kSidewindLeftDrive;
      break;
    case Motion::kSidewindRight:
      kind_ = GaitKind::kSidewind;
      drive_goal_ = -strength * kSidewindLeftDrive;
      break;
    case Motion::kRoll:
      kind_ = GaitKind::kRoll;
      drive_goal_ = strength * kRollDrive;
      break;
    case Motion::kStop:
      stopped_ = true;
      break;
  }
  Recompute();
}

void GaitController::SetDirection(double forward, double turn) {
  CheckInput("forward input", forward);
  CheckInput("turn input", turn);
  stopped_ = false;
  if (kind_ == GaitKind::kLinear) {
    drive_goal_ = forward * kForwardDrive;
    turn_ = turn;
    if (turn != 0) {
      motion_ = turn > 0 ? Motion::kTurnLeft : Motion::kTurnRight;
      strength_ = std::abs(turn);
    } else {
      motion_ = forward >= 0 ? Motion::kForward : Motion::kBackward;
      strength_ = std::abs(forward);
    }
  } else {
    const double sign =
        kind_ == GaitKind::kSidewind ? kSidewindLeftDrive : kRollDrive;
    drive_goal_ = turn * sign;
    if (kind_ == GaitKind::kSidewind) {
      motion_ = turn >= 0 ? Motion::kSidewindLeft : Motion::kSidewindRight;
      strength_ = std::abs(turn);
    } else {
      motion_ = Motion::kRoll;
      strength_ = turn;
    }
  }
  Recompute();
}

void GaitController::Recompute() {
  goal_ = JointWaves(active_gait().parameters, axes_);
  for (size_t j = 0; j < goal_.size(); ++j) {
    if (stopped_) {
      goal_[j].amplitude = 0;
      goal_[j].offset = 0;
    } else if (kind_ == GaitKind::kLinear && axes_[j] == Axis::kYaw) {
      goal_[j].offset += kLeftTurn * turn_ * options_.max_turn_offset;
    }
  }
}

void GaitController::Reset() {
  Recompute();
  waves_ = goal_;
  for (JointWave& w : waves_) {
    w.amplitude = 0;
    w.offset = 0;
  }
  targets_.assign(axes_.size(), 0.0);
  drive_ = stopped_ ? 0.0 : drive_goal_;
  phase_ = 0;
  time_ = 0;
  cpg_running_ = false;
}

void GaitController::SetFeedback(const std::vector<double>& inputs) {
  if (inputs.size() != axes_.size()) {
    throw std::invalid_argument(
        fmt::format("gait controller: {} feedback inputs for {} joints",
                    inputs.size(), axes_.size()));
  }
  for (double v : inputs) {
    if (!std::isfinite(v)) {
      throw std::invalid_argument("gait controller: feedback not finite");
    }
  }
  feedback_ = inputs;
}

void GaitController::StartCpg() {
  // Hand over from the sinusoid where it is: same phases, amplitudes,
  // offsets and frequency, so the targets do not jump.
  std::vector<double> phases(axes_.size());
  for (size_t j = 0; j < axes_.size(); ++j)
    phases[j] = phase_ + waves_[j].shift;
  cpg_.Seed(phases, waves_, drive_ / active_gait().parameters.period);
  cpg_running_ = true;
}

void GaitController::SetOscillatorPhases(const std::vector<double>& phases) {
  if (!active_gait().cpg) {
    throw std::invalid_argument("gait controller: the gait is not a CPG gait");
  }
  if (!cpg_running_) StartCpg();
  cpg_.SetPhases(phases);
}

void GaitController::UpdateCpg(double dt) {
  if (!cpg_running_) StartCpg();
  // The network smooths a drive step itself (second-order frequency).
  if (!stopped_) drive_ = drive_goal_;
  const double period = active_gait().parameters.period;
  cpg_.Step(dt, goal_, drive_ / period, *active_gait().cpg, feedback_);
  const double max_change = options_.max_target_rate * dt;
  for (size_t j = 0; j < axes_.size(); ++j) {
    const int i = static_cast<int>(j);
    // Keep the sinusoid's state in step, so leaving the CPG continues
    // from here.
    waves_[j].amplitude = std::max(0.0, cpg_.amplitudes()[j]);
    waves_[j].offset = cpg_.offsets()[j];
    waves_[j].shift = std::remainder(cpg_.phases()[j] - phase_, kTwoPi);
    const double raw = std::clamp(cpg_.output(i), -options_.target_limit,
                                  options_.target_limit);
    targets_[j] += std::clamp(raw - targets_[j], -max_change, max_change);
  }
}

bool GaitController::settled() const {
  if (!stopped_ && drive_ != drive_goal_) return false;
  if (cpg_running_) {
    // The oscillators approach their goals exponentially: settled within
    // a milliradian.
    constexpr double kTolerance = 1e-3;
    for (size_t j = 0; j < goal_.size(); ++j) {
      if (std::abs(cpg_.amplitudes()[j] - goal_[j].amplitude) > kTolerance ||
          std::abs(cpg_.offsets()[j] - goal_[j].offset) > kTolerance) {
        return false;
      }
      if (j > 0 && goal_[j].amplitude != 0 &&
          std::abs(std::remainder(cpg_.phases()[j] - cpg_.phases()[j - 1] -
                                      (goal_[j].shift - goal_[j - 1].shift),
                                  kTwoPi)) > kTolerance) {
        return false;
      }
    }
    return true;
  }
  for (size_t j = 0; j < goal_.size(); ++j) {
    if (waves_[j].amplitude != goal_[j].amplitude ||
        waves_[j].offset != goal_[j].offset) {
      return false;
    }
    if (waves_[j].amplitude != 0 && waves_[j].shift != goal_[j].shift) {
      return false;
    }
  }
  return true;
}

const std::vector<double>& GaitController::Update(double dt) {
  if (!std::isfinite(dt) || dt < 0) {
    throw std::invalid_argument(fmt::format(
        "gait controller: time step must be finite and >= 0, got {}", dt));
  }
  time_ += dt;
  if (active_gait().cpg) {
    UpdateCpg(dt);
    return targets_;
  }
  cpg_running_ = false;
  // At rest (no amplitude anywhere) the phase speed and the shifts are
  // invisible, so they take their goals at once; otherwise they ramp.
  bool at_rest = true;
  for (const JointWave& w : waves_) at_rest = at_rest && w.amplitude == 0;
  const double drive_goal = stopped_ ? drive_ : drive_goal_;
  drive_ = at_rest ? drive_goal
                   : Approach(drive_, drive_goal, options_.drive_rate * dt);
  phase_ += kTwoPi / active_gait().parameters.period * drive_ * dt;
  phase_ = std::fmod(phase_, kTwoPi);

  const double shape_step = options_.shape_rate * dt;
  const double shift_step = options_.shift_rate * dt;
  const double max_change = options_.max_target_rate * dt;
  for (size_t j = 0; j < waves_.size(); ++j) {
    JointWave& w = waves_[j];
    const JointWave& g = goal_[j];
    w.shift = w.amplitude == 0 ? g.shift
                               : ApproachAngle(w.shift, g.shift, shift_step);
    w.amplitude = Approach(w.amplitude, g.amplitude, shape_step);
    w.offset = Approach(w.offset, g.offset, shape_step);
    double raw = w.amplitude * std::sin(phase_ + w.shift) + w.offset;
    raw = std::clamp(raw, -options_.target_limit, options_.target_limit);
    targets_[j] += std::clamp(raw - targets_[j], -max_change, max_change);
  }
  return targets_;
}

}  // namespace mrsim

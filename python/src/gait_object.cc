#include "python/src/gait_object.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "gait_controller/gait_parameters.h"

namespace mrsim::python {

GaitObject::GaitObject(Gait gait) : gait_(std::move(gait)) {
  ValidateGaitParameters(gait_.parameters);
}

std::vector<Axis> GaitObject::AxesFor(int joint_count,
                                      const std::vector<Axis>& known) const {
  if (axes_) return axes_->Expand(joint_count);
  if (static_cast<int>(known.size()) == joint_count) return known;
  return JointAxesSpec("pitch-yaw").Expand(joint_count);
}

void GaitObject::SetMotion(Motion motion, double strength) {
  if (controller_) controller_->SetMotion(motion, strength);
  if (!(std::fabs(strength) <= 1.0)) {
    throw std::invalid_argument("strength: expected a number in [-1, 1]");
  }
  motion_ = std::make_pair(motion, strength);
}

void GaitObject::SetDirection(double forward, double turn) {
  if (controller_) controller_->SetDirection(forward, turn);
  if (!(std::fabs(forward) <= 1.0) || !(std::fabs(turn) <= 1.0)) {
    throw std::invalid_argument("forward, turn: expected numbers in [-1, 1]");
  }
  direction_ = std::make_pair(forward, turn);
}

void GaitObject::SetParameters(const GaitParameters& parameters) {
  ValidateGaitParameters(parameters);
  if (controller_) controller_->SetParameters(parameters);
  gait_.parameters = parameters;
  gait_.name = "custom";
}

const std::vector<double>& GaitObject::TargetsAt(
    double t, const std::vector<Axis>& axes) {
  if (!std::isfinite(t) || t < 0) {
    throw std::invalid_argument("t: expected a finite time >= 0 (s)");
  }
  if (!controller_) {
    auto c = std::make_unique<GaitController>(axes);
    c->SetGait(gait_);
    if (motion_) c->SetMotion(motion_->first, motion_->second);
    if (direction_) c->SetDirection(direction_->first, direction_->second);
    controller_ = std::move(c);
    have_last_ = false;
  } else if (axes.size() != controller_->joint_axes().size()) {
    throw std::invalid_argument(
        "the state has " + std::to_string(axes.size()) +
        " joints, the gait runs " +
        std::to_string(controller_->joint_axes().size()) +
        " (call reset() for another robot)");
  }
  if (have_last_ && t < last_time_) {
    // A reset or a loaded checkpoint: as mrsim-gait, start from rest.
    controller_->Reset();
    have_last_ = false;
  }
  const double dt = have_last_ ? t - last_time_ : 0.0;
  last_time_ = t;
  have_last_ = true;
  return controller_->Update(dt);
}

void GaitObject::Reset() {
  controller_.reset();
  have_last_ = false;
}

}  // namespace mrsim::python

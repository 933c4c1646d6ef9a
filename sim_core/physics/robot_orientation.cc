#include "sim_core/physics/robot_orientation.h"

#include <cmath>

namespace mrsim {

double HeadingOf(const Eigen::Quaterniond& orientation) {
  const Eigen::Vector3d x = orientation * Eigen::Vector3d::UnitX();
  // Below this the forward axis is vertical and atan2 would return noise.
  if (std::hypot(x.x(), x.y()) < 1e-9) return 0.0;
  return std::atan2(x.y(), x.x());
}

void FillRobotOrientation(RobotState* state) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  if (!state->frames.empty()) {
    q = state->frames.front().orientation;
  } else if (!state->sensor_modules.empty()) {
    q = state->sensor_modules.front().pose.orientation;
  }
  q.normalize();
  // One sign for the same rotation, so logged columns do not flip between
  // q and -q: w >= 0.
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  state->orientation = q;
  state->heading = HeadingOf(q);
}

}  // namespace mrsim

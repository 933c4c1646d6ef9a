#include "studio/design/euler_degrees.h"

#include <algorithm>
#include <cmath>

namespace mrsim::studio {
namespace {

constexpr double kDegree = M_PI / 180;

// -0 shows as "-0" in a field; a student typed 0.
double Tidy(double degrees) { return degrees == 0 ? 0 : degrees; }

}  // namespace

Eigen::Quaterniond QuaternionFromEulerDegrees(const Eigen::Vector3d& rpy) {
  const Eigen::Vector3d r = rpy * kDegree;
  return Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX());
}

Eigen::Vector3d EulerDegreesFromQuaternion(const Eigen::Quaterniond& q) {
  if (q.coeffs().squaredNorm() == 0) return Eigen::Vector3d::Zero();
  const Eigen::Quaterniond u = q.normalized();
  const double w = u.w(), x = u.x(), y = u.y(), z = u.z();
  const double sin_pitch = 2 * (w * y - z * x);
  double roll = 0, pitch = 0, yaw = 0;
  if (std::abs(sin_pitch) < 1 - 1e-12) {
    roll = std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
    pitch = std::asin(sin_pitch);
    yaw = std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
  } else {
    // Straight up or down: roll and yaw turn about the same axis and the
    // formulas above divide rounding noise by rounding noise. The whole
    // turn goes to yaw, read from the rotation's second column.
    pitch = std::copysign(M_PI / 2, sin_pitch);
    const Eigen::Matrix3d r = u.toRotationMatrix();
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  return Eigen::Vector3d(Tidy(roll / kDegree), Tidy(pitch / kDegree),
                         Tidy(yaw / kDegree));
}

}  // namespace mrsim::studio

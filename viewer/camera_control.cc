#include "viewer/camera_control.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace mrsim {

CameraControl::CameraControl(const CameraSettings& settings)
    : start_(settings) {
  mjv_defaultCamera(&camera_);
  camera_.type = mjCAMERA_FREE;
  Reset();
}

void CameraControl::Reset() {
  mode_ = start_.mode;
  azimuth_ = start_.azimuth;
  elevation_ = std::clamp(start_.elevation, -89.0, 89.0);
  distance_ = std::clamp(start_.distance, 0.05, 100.0);
  offset_ = start_.lookat;
  Apply();
}

void CameraControl::ToggleMode() {
  // Keep the view where it is; only what it is anchored to changes.
  const Eigen::Vector3d here = lookat();
  mode_ =
      mode_ == CameraMode::kFollow ? CameraMode::kFixed : CameraMode::kFollow;
  offset_ = mode_ == CameraMode::kFixed ? here : here - target_;
  Apply();
}

void CameraControl::Track(const Eigen::Vector3d& target) {
  if (!target.allFinite()) return;
  target_ = target;
  Apply();
}

void CameraControl::Orbit(double d_azimuth, double d_elevation) {
  azimuth_ = std::fmod(azimuth_ + d_azimuth, 360.0);
  elevation_ = std::clamp(elevation_ + d_elevation, -89.0, 89.0);
  Apply();
}

void CameraControl::Pan(double right, double up) {
  const double az = azimuth_ * M_PI / 180.0;
  const double el = elevation_ * M_PI / 180.0;
  const Eigen::Vector3d forward(std::cos(el) * std::cos(az),
                                std::cos(el) * std::sin(az), std::sin(el));
  const Eigen::Vector3d right_dir =
      forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d up_dir = right_dir.cross(forward);
  offset_ += distance_ * (right * right_dir + up * up_dir);
  Apply();
}

void CameraControl::Zoom(double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  distance_ = std::clamp(distance_ * factor, 0.05, 100.0);
  Apply();
}

Eigen::Vector3d CameraControl::lookat() const {
  return mode_ == CameraMode::kFollow ? Eigen::Vector3d(target_ + offset_)
                                      : offset_;
}

void CameraControl::Apply() {
  const Eigen::Vector3d at = lookat();
  for (int i = 0; i < 3; ++i) camera_.lookat[i] = at[i];
  camera_.azimuth = azimuth_;
  camera_.elevation = elevation_;
  camera_.distance = distance_;
}

}  // namespace mrsim

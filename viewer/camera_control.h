// The viewer's camera: follows a point (the robot's centre of mass) or stays
// fixed, and is orbited, panned and zoomed by the window or by flags.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>

namespace mrsim {

enum class CameraMode { kFollow, kFixed };

// Starting view. Angles in degrees as MuJoCo's free camera uses them:
// azimuth about +z from +x, elevation negative when looking down.
struct CameraSettings {
  CameraMode mode = CameraMode::kFollow;
  double azimuth = 135.0;
  double elevation = -25.0;
  double distance = 1.5;  // m from the look-at point
  // Fixed mode: the look-at point. Follow mode: an offset from the tracked
  // point (zero keeps it centred).
  Eigen::Vector3d lookat = Eigen::Vector3d::Zero();
};

class CameraControl {
 public:
  explicit CameraControl(const CameraSettings& settings);

  // Follow mode: the camera looks at `target` plus the pan offset. Fixed
  // mode ignores it.
  void Track(const Eigen::Vector3d& target);
  // Orbit by angles in degrees (positive: azimuth left, elevation up).
  void Orbit(double d_azimuth, double d_elevation);
  // Moves the look-at point across the view by fractions of the distance
  // (positive: right, up).
  void Pan(double right, double up);
  // Multiplies the distance by `factor` (< 1 zooms in); kept in
  // [0.05, 100] m.
  void Zoom(double factor);
  // Back to the starting view.
  void Reset();
  void ToggleMode();

  CameraMode mode() const { return mode_; }
  const mjvCamera& camera() const { return camera_; }
  Eigen::Vector3d lookat() const;

 private:
  void Apply();

  CameraSettings start_;
  CameraMode mode_;
  double azimuth_;
  double elevation_;
  double distance_;
  Eigen::Vector3d offset_;  // follow: from target; fixed: absolute
  Eigen::Vector3d target_ = Eigen::Vector3d::Zero();
  mjvCamera camera_;
};

}  // namespace mrsim

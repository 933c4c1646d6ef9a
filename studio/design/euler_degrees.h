// A rotation as a student types it: roll, pitch and yaw in degrees, turned
// about the fixed x axis, then y, then z. The scenario keeps quaternions
// (x y z w in files, w x y z in messages); these two functions are the only
// place the inspector's degrees meet them.
#pragma once

#include <Eigen/Geometry>

namespace mrsim::studio {

// The convention in words, for tooltips and docs.
inline constexpr const char* kEulerConvention =
    "roll, pitch, yaw in degrees: turned about x, then y, then z (fixed "
    "axes); stored as a quaternion";

// Degrees (roll about x, pitch about y, yaw about z) to a unit quaternion
// q = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Quaterniond QuaternionFromEulerDegrees(const Eigen::Vector3d& rpy);

// The inverse, with pitch in [-90, 90] and roll and yaw in (-180, 180]. The
// quaternion need not be unit length; all zeros (a file's "none given")
// reads as no turn.
Eigen::Vector3d EulerDegreesFromQuaternion(const Eigen::Quaterniond& q);

}  // namespace mrsim::studio

// Two boxes that share a whole face (aligned, the same cross-section, flush)
// fill exactly one box. The MJCF builder gives each rigid pair of module
// frames that lie so one contact box: a locked pair flat on the ground then
// touches it at its four outer corners instead of eight, half of them
// doubled up where the frames meet (docs/physics.md, "Contacts").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace mrsim {

struct OrientedBox {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Quaterniond quat = Eigen::Quaterniond::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();  // half sizes, box axes
};

// The box both fill, in a's axes, or nothing when they do not fill one box
// (rotated against each other other than by quarter turns, different
// cross-sections, a gap, an overlap or an offset). `tolerance` is relative
// to the larger box's largest half size.
std::optional<OrientedBox> FlushBoxUnion(const OrientedBox& a,
                                         const OrientedBox& b,
                                         double tolerance = 1e-6);

}  // namespace mrsim

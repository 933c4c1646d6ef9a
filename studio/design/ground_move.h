// Moving whole robots and objects on the ground, as the 3-D view's move
// handle and heading ring do: a shift in x and y and a turn about the
// vertical (z) through a pivot. Only poses change; what the parts are and
// how they are joined stays. No window: the studio's drag and its tests
// both call these.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "sim_core/scenario/scenario.h"
#include "studio/design/selection.h"

namespace mrsim::studio {

// A move on the ground: `shift` (m, x and y) and `turn` (rad, about +z,
// counter-clockwise seen from above) about the pivot.
struct GroundMove {
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  double turn = 0.0;

  bool empty() const { return shift.isZero(0) && turn == 0.0; }
};

// The rigid transform a move makes of a part turning about `pivot`.
Eigen::Isometry3d GroundTransform(const Eigen::Vector3d& pivot,
                                  const GroundMove& move);

// Where the robot turns about: the mean of its hinges and sensor-module
// centres (zero for an empty robot).
Eigen::Vector3d RobotPivot(const Robot& robot);
// The direction module 0's first frame points along (its x axis, the
// chain's front-to-back line), as an angle about +z from +x (rad); 0 for an
// empty robot. A chain as `mrsim-scenario new` makes it has heading 0.
double RobotHeading(const Robot& robot);

// Moves every part of `robot` (hinges, frames, sensor modules and what is
// mounted on them) by `transform`.
void TransformRobot(Robot* robot, const Eigen::Isometry3d& transform);
// Moves a sensor module and what is mounted on it by `transform`.
void TransformSensorModule(SensorModule* sm,
                           const Eigen::Isometry3d& transform);
// Moves the robot about its own pivot.
void MoveRobot(Robot* robot, const GroundMove& move);
// Moves the object about its own centre (its Euler `rotation` z follows a
// turn, in degrees, as the original stored it).
void MoveObject(SceneObject* object, const GroundMove& move);

// The loose parts that move together with the one `selection` names (a
// loose frame or sensor module, or a loose joint: the parts it joins):
// it and every loose part joined to it through loose joints, as
// kLooseFrame and kLooseSensorModule selections, frames first. Empty for
// any other selection or one out of range. A hinge pair is dragged as one.
std::vector<Selection> LooseGroup(const Scenario& s,
                                  const Selection& selection);
// Where a loose group turns about: the mean of its parts' centres.
Eigen::Vector3d LoosePivot(const Scenario& s,
                           const std::vector<Selection>& group);
// Moves every part of `group` about the group's pivot.
void MoveLooseGroup(Scenario* s, const std::vector<Selection>& group,
                    const GroundMove& move);

}  // namespace mrsim::studio

// What the user has selected in the studio: one part of the scenario, named
// by kind and position in the scenario's lists (the 3-D view and the
// inspector share it).
#pragma once

#include <string>

#include "sim_core/scenario/scenario_schema.h"

namespace mrsim::studio {

// Where the selection kinds of loose parts start (see SelectionKind).
inline constexpr int kLoosePartKinds = 1000;

// What kind of part a selection names: nothing, or one of the scenario
// schema's part kinds (mrsim::PartKind, the one list of kinds) that the
// studio lets a user pick, each with the schema kind's value, so a
// selection kind cannot name a part the schema does not describe.
enum class SelectionKind {
  kNone = -1,
  kRobot = static_cast<int>(PartKind::kRobot),  // robot
  // robot, index into Robot::modules
  kModule = static_cast<int>(PartKind::kModule),
  // robot, index into Robot::sensor_modules
  kSensorModule = static_cast<int>(PartKind::kSensorModule),
  // index into Scenario::scene_objects
  kSceneObject = static_cast<int>(PartKind::kSceneObject),
  kScene = static_cast<int>(PartKind::kScene),  // the terrain
  // index into Scenario::fluid_regions
  kFluidRegion = static_cast<int>(PartKind::kFluidRegion),
  // index into Scenario::contact_frictions
  kContactFriction = static_cast<int>(PartKind::kContactFriction),
  kSettings = static_cast<int>(PartKind::kSettings),  // Scenario::settings
  // robot, index into Robot::locks (a lock between two of its parts)
  kLock = static_cast<int>(PartKind::kJoint),
  // index into Scenario::loose_frames
  kLooseFrame = static_cast<int>(PartKind::kFrame),
  // Parts without a robot whose schema kind a robot's part already takes:
  // the kind's value past every PartKind.
  // index into Scenario::loose_joints
  kLooseJoint = kLoosePartKinds + static_cast<int>(PartKind::kJoint),
  // index into Scenario::loose_sensor_modules
  kLooseSensorModule =
      kLoosePartKinds + static_cast<int>(PartKind::kSensorModule),
};

struct Selection {
  SelectionKind kind = SelectionKind::kNone;
  int robot = 0;
  int index = 0;

  bool operator==(const Selection& o) const {
    return kind == o.kind && robot == o.robot && index == o.index;
  }
  bool operator!=(const Selection& o) const { return !(*this == o); }
};

// "module 2 of snake", "ball (object 0)", ...: for titles and test dumps.
const char* ToString(SelectionKind kind);

}  // namespace mrsim::studio

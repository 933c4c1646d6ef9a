// What the user has selected in the studio: one part of the scenario, named
// by kind and position in the scenario's lists (the 3-D view and the
// inspector share it).
#pragma once

#include <string>

namespace mrsim::studio {

enum class PartKind {
  kNone,
  kRobot,         // robot
  kModule,        // robot, index into Robot::modules
  kSensorModule,  // robot, index into Robot::sensor_modules
  kObject,        // index into Scenario::scene_objects
  kScene,         // the terrain
  kFluid,         // index into Scenario::fluid_regions
  kContact,       // index into Scenario::contact_frictions
  kSettings,      // Scenario::settings
};

struct Selection {
  PartKind kind = PartKind::kNone;
  int robot = 0;
  int index = 0;

  bool operator==(const Selection& o) const {
    return kind == o.kind && robot == o.robot && index == o.index;
  }
  bool operator!=(const Selection& o) const { return !(*this == o); }
};

// "module 2 of snake", "ball (object 0)", ...: for titles and test dumps.
const char* ToString(PartKind kind);

}  // namespace mrsim::studio

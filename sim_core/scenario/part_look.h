// The colour of each kind of part, one hue per kind: the MJCF builder shades
// it per scenario material, and tools that show a kind's colour outside the
// model (the studio's palette, the viewer) read the same hue here.
#pragma once

#include <Eigen/Core>

namespace mrsim {

enum class PartLook {
  kPitchModule,
  kYawModule,
  kLooseFrame,
  kSensorModule,
  kForcePlate,
  kDistanceSensor,
  kSceneObject,
};
Eigen::Vector3d PartLookRgb(PartLook kind);

}  // namespace mrsim

#include "sim_core/scenario/part_look.h"

namespace mrsim {

// Hues far apart on the wheel so neighbours in a chain stand out: warm
// orange pitch, blue yaw, green sensor modules, magenta plates, yellow
// distance sensors, red scene objects, grey loose frames.
Eigen::Vector3d PartLookRgb(PartLook kind) {
  switch (kind) {
    case PartLook::kPitchModule:
      return {0.95, 0.55, 0.15};
    case PartLook::kYawModule:
      return {0.2, 0.45, 0.9};
    case PartLook::kLooseFrame:
      return {0.6, 0.6, 0.6};
    case PartLook::kSensorModule:
      return {0.25, 0.75, 0.3};
    case PartLook::kForcePlate:
      return {0.8, 0.25, 0.8};
    case PartLook::kDistanceSensor:
      return {1.0, 0.9, 0.2};
    case PartLook::kSceneObject:
      return {0.85, 0.2, 0.2};
  }
  return {0.5, 0.5, 0.5};
}

}  // namespace mrsim

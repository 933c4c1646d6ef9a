// The faces of a sensor module, numbered as sensorPosition in the scenario
// file: one list for the schema, the validator, the builder and the studio.
#pragma once

#include <array>

namespace mrsim {

inline constexpr std::array<const char*, 6> kSensorFaceNames = {
    "bottom", "left", "top", "right", "front", "back"};
// The same as the schema gives the names of the values (distance sensors
// take every face, a force plate the first four).
inline constexpr char kSensorFaceList[] =
    "bottom, left, top, right, front, back";
inline constexpr char kForcePlateFaceList[] = "bottom, left, top, right";

}  // namespace mrsim

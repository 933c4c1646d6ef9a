// LCM channel names. Every channel starts with a prefix (default "MRSIM") so
// several simulations can share a network; robot channels end in the robot
// name so several robots can share a simulation.
#pragma once

#include <string>

namespace mrsim {

inline constexpr const char* kDefaultChannelPrefix = "MRSIM";

inline std::string StateChannel(const std::string& prefix,
                                const std::string& robot) {
  return prefix + "_STATE_" + robot;
}
inline std::string CommandChannel(const std::string& prefix,
                                  const std::string& robot) {
  return prefix + "_COMMAND_" + robot;
}
// Run-time gait changes for one robot's mrsim-gait (gait_command_t).
inline std::string GaitChannel(const std::string& prefix,
                               const std::string& robot) {
  return prefix + "_GAIT_" + robot;
}
// What one robot's mrsim-gait runs (gait_status_t).
inline std::string GaitStatusChannel(const std::string& prefix,
                                     const std::string& robot) {
  return prefix + "_GAIT_STATUS_" + robot;
}
// Poses of the movable scene objects (scene_state_t).
inline std::string SceneChannel(const std::string& prefix) {
  return prefix + "_SCENE";
}
inline std::string SimControlChannel(const std::string& prefix) {
  return prefix + "_SIM_CONTROL";
}
inline std::string SimStatusChannel(const std::string& prefix) {
  return prefix + "_SIM_STATUS";
}

}  // namespace mrsim

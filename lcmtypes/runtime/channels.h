// LCM channel names. Every channel starts with a prefix (default "MRSIM") so
// several simulations can share a network; robot channels end in the robot
// name so several robots can share a simulation. Each message's channel is
// declared in its .lcm file (`// channel: <prefix>_STATE_<robot>`);
// kChannels is that table (mrsim/channel_table.hpp, generated), the one the
// programs, Python (mrsim._core.channels()) and the docs read.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "mrsim/channel_table.hpp"

namespace mrsim {

inline constexpr const char* kDefaultChannelPrefix = "MRSIM";

// One message type's channel: <prefix><infix>[<suffix>].
struct ChannelSpec {
  const char* type;     // the .lcm type, "robot_state_t"
  const char* name;     // short name, "state"
  const char* pattern;  // "<prefix>_STATE_<robot>"
  const char* infix;    // "_STATE_"
  // What ends the name: "robot" (a robot's name), "shard" (the farm's job
  // shard, two hex digits) or "" (nothing).
  const char* suffix;
  const char* default_prefix;  // "MRSIM", or the farm's "MRSIM_OPT"
};

#define MRSIM_CHANNEL_SPEC(type, name, pattern, infix, suffix, prefix) \
  ChannelSpec{#type, name, pattern, infix, suffix, prefix},
inline constexpr ChannelSpec kChannels[] = {
    MRSIM_CHANNEL_TABLE(MRSIM_CHANNEL_SPEC)};
#undef MRSIM_CHANNEL_SPEC

// The channel named `name` ("state"); a name not in the table does not
// compile where it is used in a constant expression.
constexpr const ChannelSpec& ChannelNamed(std::string_view name) {
  for (const ChannelSpec& c : kChannels) {
    if (name == c.name) return c;
  }
  throw "no such channel in the .lcm files' '// channel:' lines";
}

// <prefix><infix>[<suffix>] of a channel of the table.
inline std::string ChannelName(const ChannelSpec& spec,
                               const std::string& prefix,
                               const std::string& suffix = "") {
  return prefix + spec.infix + (*spec.suffix != '\0' ? suffix : "");
}

inline std::string StateChannel(const std::string& prefix,
                                const std::string& robot) {
  static constexpr const ChannelSpec& kSpec = ChannelNamed("state");
  return ChannelName(kSpec, prefix, robot);
}
inline std::string CommandChannel(const std::string& prefix,
                                  const std::string& robot) {
  static constexpr const ChannelSpec& kSpec = ChannelNamed("command");
  return ChannelName(kSpec, prefix, robot);
}
// Run-time gait changes for one robot's mrsim-gait (gait_command_t).
inline std::string GaitChannel(const std::string& prefix,
                               const std::string& robot) {
  static constexpr const ChannelSpec& kSpec = ChannelNamed("gait");
  return ChannelName(kSpec, prefix, robot);
}
// What one robot's mrsim-gait runs (gait_status_t).
inline std::string GaitStatusChannel(const std::string& prefix,
                                     const std::string& robot) {
  static constexpr const ChannelSpec& kSpec = ChannelNamed("gait_status");
  return ChannelName(kSpec, prefix, robot);
}
// Poses of the movable scene objects (scene_state_t).
inline std::string SceneChannel(const std::string& prefix) {
  static constexpr const ChannelSpec& kSpec = ChannelNamed("scene");
  return ChannelName(kSpec, prefix);
}
inline std::string SimControlChannel(const std::string& prefix) {
  static constexpr const ChannelSpec& kSpec = ChannelNamed("sim_control");
  return ChannelName(kSpec, prefix);
}
inline std::string SimStatusChannel(const std::string& prefix) {
  static constexpr const ChannelSpec& kSpec = ChannelNamed("sim_status");
  return ChannelName(kSpec, prefix);
}

}  // namespace mrsim

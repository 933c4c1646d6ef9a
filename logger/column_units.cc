#include "logger/column_units.h"

#include <cctype>
#include <string_view>

#include "mrsim/field_units.hpp"
#include "sim_core/scenario/sensor_kind.h"

namespace mrsim {
namespace {

constexpr const char* kRobotState = "mrsim.robot_state_t";
constexpr const char* kPose = "mrsim.pose_t";
constexpr const char* kJoint = "mrsim.joint_state_t";

std::optional<std::string> FieldUnit(const char* type, const char* field) {
  const char* unit = FindLcmFieldUnit(type, field);
  if (unit == nullptr) return std::nullopt;
  return std::string(unit);
}

// Removes `word` and the decimal index after it from the front of `s`
// ("module12.x" -> ".x"); false when s does not start so.
bool EatIndexed(std::string_view* s, std::string_view word) {
  if (s->substr(0, word.size()) != word) return false;
  size_t i = word.size();
  while (i < s->size() && std::isdigit(static_cast<unsigned char>((*s)[i]))) {
    ++i;
  }
  if (i == word.size()) return false;
  s->remove_prefix(i);
  return true;
}

bool Eat(std::string_view* s, std::string_view word) {
  if (s->substr(0, word.size()) != word) return false;
  s->remove_prefix(word.size());
  return true;
}

// ".x" .. ".qz" of a pose (the flattener's kPoseNames): pose_t's fields.
std::optional<std::string> PoseMemberUnit(std::string_view rest) {
  if (rest == ".x" || rest == ".y" || rest == ".z") {
    return FieldUnit(kPose, "position");
  }
  if (rest == ".qw" || rest == ".qx" || rest == ".qy" || rest == ".qz") {
    return FieldUnit(kPose, "orientation");
  }
  return std::nullopt;
}

// ".angle", ".speed", ".torque" or a pose member: a joint_state_t.
std::optional<std::string> JointMemberUnit(std::string_view rest) {
  for (const char* field : {"angle", "speed", "torque"}) {
    if (rest.size() > 1 && rest[0] == '.' && rest.substr(1) == field) {
      return FieldUnit(kJoint, field);
    }
  }
  return PoseMemberUnit(rest);
}

// What follows "sensor_module<k>": its pose, or one value of a sensor kind
// named as SensorValueName names it (a second distance sensor on one face
// gets "_<j>").
std::optional<std::string> SensorModuleMemberUnit(std::string_view rest) {
  if (auto unit = PoseMemberUnit(rest)) return unit;
  for (const SensorKind& kind : SensorKinds()) {
    for (int face = -1; face < 6; ++face) {
      for (const SensorChannel& channel : kind.channels) {
        const std::string name = SensorValueName("", kind, face, channel);
        if (rest.substr(0, name.size()) != name) continue;
        std::string_view tail = rest.substr(name.size());
        if (tail.empty() ||
            (tail[0] == '_' && tail.size() > 1 &&
             tail.find_first_not_of("0123456789", 1) == std::string::npos)) {
          return std::string(channel.unit);
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> FindColumnUnit(const std::string& column) {
  std::string_view s = column;
  // Every CSV's first column: the message's utime (us) in seconds.
  if (s == "time") return std::string("s");
  if (s == "robot") return std::string();  // text
  for (const char* field : {"seq", "sim_time", "heading"}) {
    if (s == field) return FieldUnit(kRobotState, field);
  }
  for (const char* field : {"com", "com_velocity"}) {
    std::string_view rest = s;
    if (Eat(&rest, field) && (rest == ".x" || rest == ".y" || rest == ".z")) {
      return FieldUnit(kRobotState, field);
    }
  }
  if (Eat(&s, "orientation")) {
    if (PoseMemberUnit(s) && s[1] == 'q') {
      return FieldUnit(kRobotState, "orientation");
    }
    return std::nullopt;
  }
  if (Eat(&s, "lock.")) {
    const std::string_view suffix = ".attached";
    if (s.size() > suffix.size() &&
        s.substr(s.size() - suffix.size()) == suffix) {
      return FieldUnit(kRobotState, "lock_attached");
    }
    return std::nullopt;
  }
  if (EatIndexed(&s, "sensor_module")) return SensorModuleMemberUnit(s);
  if (EatIndexed(&s, "module")) {
    if (Eat(&s, ".joint")) return JointMemberUnit(s);
    if (EatIndexed(&s, ".frame")) return PoseMemberUnit(s);
    return PoseMemberUnit(s);
  }
  if (EatIndexed(&s, "frame")) return PoseMemberUnit(s);
  if (EatIndexed(&s, "joint")) return JointMemberUnit(s);
  return std::nullopt;
}

std::string ColumnUnit(const std::string& column) {
  const std::optional<std::string> unit = FindColumnUnit(column);
  return unit && *unit != "1" ? *unit : std::string();
}

std::string ColumnLabel(const std::string& column) {
  const std::string unit = ColumnUnit(column);
  return unit.empty() ? column : column + " [" + unit + "]";
}

}  // namespace mrsim

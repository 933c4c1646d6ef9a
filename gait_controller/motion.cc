#include "gait_controller/motion.h"

#include <algorithm>
#include <array>
#include <utility>

namespace mrsim {

namespace {

constexpr std::array<std::pair<Motion, const char*>, 8> kMotionNames = {{
    {Motion::kForward, "forward"},
    {Motion::kBackward, "backward"},
    {Motion::kTurnLeft, "turn-left"},
    {Motion::kTurnRight, "turn-right"},
    {Motion::kSidewindLeft, "sidewind-left"},
    {Motion::kSidewindRight, "sidewind-right"},
    {Motion::kRoll, "roll"},
    {Motion::kStop, "stop"},
}};

constexpr std::array<std::pair<GaitKind, const char*>, 3> kKindNames = {{
    {GaitKind::kLinear, "linear"},
    {GaitKind::kSidewind, "sidewind"},
    {GaitKind::kRoll, "roll"},
}};

std::string Dashed(std::string text) {
  std::replace(text.begin(), text.end(), '_', '-');
  return text;
}

}  // namespace

const char* ToString(Motion motion) {
  for (const auto& [m, name] : kMotionNames) {
    if (m == motion) return name;
  }
  return "?";
}

std::optional<Motion> ParseMotion(const std::string& text) {
  const std::string t = Dashed(text);
  for (const auto& [m, name] : kMotionNames) {
    if (t == name) return m;
  }
  return std::nullopt;
}

const char* ToString(GaitKind kind) {
  for (const auto& [k, name] : kKindNames) {
    if (k == kind) return name;
  }
  return "?";
}

std::optional<GaitKind> ParseGaitKind(const std::string& text) {
  for (const auto& [k, name] : kKindNames) {
    if (text == name) return k;
  }
  return std::nullopt;
}

}  // namespace mrsim

#include "tools/gait_command_request.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "gait_controller/motion.h"

namespace mrsim {
namespace {

double Number(const std::vector<std::string>& words, size_t i,
              const std::string& what, double lo, double hi) {
  if (i >= words.size()) throw std::invalid_argument(what + ": missing value");
  char* end = nullptr;
  const double v = std::strtod(words[i].c_str(), &end);
  if (words[i].empty() || *end != '\0' || !std::isfinite(v)) {
    throw std::invalid_argument(what + ": expected a number, got '" + words[i] +
                                "'");
  }
  if (v < lo || v > hi) {
    throw std::invalid_argument(
        fmt::format("{}: expected a number in [{:g}, {:g}], got '{}'", what, lo,
                    hi, words[i]));
  }
  return v;
}

}  // namespace

const char* GaitRequestUsage() {
  return "gait ROBOT [gait NAME] [motion M] [strength S] [direction F T]";
}

gait_command_t ParseGaitRequest(const std::vector<std::string>& words) {
  if (words.size() < 3) {
    throw std::invalid_argument(std::string("expected ") + GaitRequestUsage());
  }
  gait_command_t c{};
  c.robot = words[1];
  c.strength = 1.0;
  for (size_t i = 2; i < words.size(); ++i) {
    const std::string& key = words[i];
    if (key == "gait" && i + 1 < words.size()) {
      c.gait = words[++i];
    } else if (key == "motion" && i + 1 < words.size()) {
      c.motion = words[++i];
      if (!ParseMotion(c.motion)) {
        throw std::invalid_argument(
            "motion: unknown '" + c.motion +
            "'; expected forward, backward, turn-left, turn-right, "
            "sidewind-left, sidewind-right, roll or stop");
      }
    } else if (key == "strength") {
      c.strength = Number(words, ++i, "strength", -1, 1);
    } else if (key == "direction") {
      c.has_direction = true;
      c.forward = Number(words, ++i, "direction forward", -1, 1);
      c.turn = Number(words, ++i, "direction turn", -1, 1);
    } else {
      throw std::invalid_argument("gait: unexpected '" + key +
                                  "'; expected gait NAME, motion M, "
                                  "strength S or direction F T");
    }
  }
  return c;
}

}  // namespace mrsim

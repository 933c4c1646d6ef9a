#include "gait_controller/process/key_command.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "gait_controller/gait_presets.h"

namespace mrsim {
namespace {

gait_command_t MotionCommand(const std::string& motion, double strength) {
  gait_command_t c{};
  c.sender = "keyboard";
  c.motion = motion;
  c.strength = strength;
  return c;
}

}  // namespace

const char* KeyHelp() {
  return "keys: Up forward, Down backward, Left/Right turn (again: sharper), "
         "a/d sidewind left/right, r roll, space or s stop, +/- "
         "faster/slower, 1-8 presets, h help, q quit";
}

std::optional<gait_command_t> KeyCommand(const Key& key,
                                         const GaitController* c, bool* quit,
                                         bool* help) {
  const Motion motion = c ? c->motion() : Motion::kForward;
  const double strength = c ? std::abs(c->strength()) : 1.0;
  auto turn = [&](Motion m, const char* name) {
    const double s = motion == m ? std::min(1.0, strength + 0.25) : 0.5;
    return MotionCommand(name, s);
  };
  switch (key.code) {
    case KeyCode::kUp:
      return MotionCommand("forward", 1.0);
    case KeyCode::kDown:
      return MotionCommand("backward", 1.0);
    case KeyCode::kLeft:
      return turn(Motion::kTurnLeft, "turn-left");
    case KeyCode::kRight:
      return turn(Motion::kTurnRight, "turn-right");
    case KeyCode::kChar:
      break;
  }
  switch (key.ch) {
    case 'a':
      return MotionCommand("sidewind-left", 1.0);
    case 'd':
      return MotionCommand("sidewind-right", 1.0);
    case 'r':
      return MotionCommand("roll", 1.0);
    case ' ':
    case 's':
      return MotionCommand("stop", 1.0);
    case '+':
    case '=':
    case '-': {
      if (!c || c->stopped()) return std::nullopt;
      const double step = key.ch == '-' ? -0.25 : 0.25;
      const double s = std::clamp(strength + step, 0.25, 1.0);
      return MotionCommand(ToString(motion), s);
    }
    case 'q':
      *quit = true;
      return std::nullopt;
    case 'h':
    case '?':
      *help = true;
      return std::nullopt;
    default:
      break;
  }
  if (key.ch >= '1' && key.ch <= '9') {
    const size_t i = static_cast<size_t>(key.ch - '1');
    if (i < GaitPresets().size()) {
      gait_command_t g{};
      g.sender = "keyboard";
      g.gait = GaitPresets()[i].name;
      return g;
    }
  }
  return std::nullopt;
}

}  // namespace mrsim

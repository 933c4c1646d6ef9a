#include "tools/sim_control_request.h"

#include <cmath>
#include <cstdlib>

#include "common/edit_distance.h"
#include "tools/gait_command_request.h"

namespace mrsim {
namespace {

std::string Expect(const std::vector<std::string>& words, size_t n,
                   const char* what) {
  if (words.size() != n + 1) {
    throw std::invalid_argument("'" + words[0] + "' takes " + what);
  }
  return n == 0 ? "" : words[1];
}

double Number(const std::string& text, const std::string& command) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v)) {
    throw std::invalid_argument("'" + command + "': expected a number, got '" +
                                text + "'");
  }
  return v;
}

}  // namespace

const char* SimControlUsage() {
  return "pause | resume | step N | reset | save PATH | load PATH | speed S "
         "| detach ROBOT LOCK | attach ROBOT LOCK | quit";
}

sim_control_t ParseSimControl(const std::vector<std::string>& words) {
  if (words.empty()) {
    throw std::invalid_argument(std::string("no command; expected ") +
                                SimControlUsage());
  }
  sim_control_t msg{};
  const std::string& c = words[0];
  if (c == "pause") {
    Expect(words, 0, "no argument");
    msg.command = sim_control_t::PAUSE;
  } else if (c == "resume") {
    Expect(words, 0, "no argument");
    msg.command = sim_control_t::RESUME;
  } else if (c == "step") {
    const double n = Number(Expect(words, 1, "a number of control periods"), c);
    if (n < 1 || n != std::floor(n) || n > 1e9) {
      throw std::invalid_argument(
          "'step': expected a whole number >= 1, got '" + words[1] + "'");
    }
    msg.command = sim_control_t::STEP;
    msg.steps = static_cast<int32_t>(n);
  } else if (c == "reset") {
    Expect(words, 0, "no argument");
    msg.command = sim_control_t::RESET;
  } else if (c == "save" || c == "load") {
    msg.path = Expect(words, 1, "a checkpoint path");
    msg.command = c == "save" ? sim_control_t::SAVE_CHECKPOINT
                              : sim_control_t::LOAD_CHECKPOINT;
  } else if (c == "speed") {
    msg.speed = Number(Expect(words, 1, "a real-time factor"), c);
    if (msg.speed <= 0) {
      throw std::invalid_argument("'speed': expected a factor > 0, got '" +
                                  words[1] + "'");
    }
    msg.command = sim_control_t::SET_SPEED;
  } else if (c == "detach" || c == "attach") {
    if (words.size() != 3) {
      throw std::invalid_argument("'" + c +
                                  "' takes a robot and a lock name (as the "
                                  "robot's state lists them)");
    }
    msg.command = c == "detach" ? sim_control_t::DETACH : sim_control_t::ATTACH;
    msg.robot = words[1];
    msg.lock = words[2];
  } else if (c == "quit") {
    Expect(words, 0, "no argument");
    msg.command = sim_control_t::QUIT;
  } else {
    const std::string nearest =
        NearestWord(c, {"pause", "resume", "step", "reset", "save", "load",
                        "speed", "detach", "attach", "quit", "status", "gait"});
    throw std::invalid_argument(
        "unknown command '" + c + "'" +
        (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)") +
        "; the commands are: " + SimControlUsage() + " | status | " +
        GaitRequestUsage());
  }
  return msg;
}

}  // namespace mrsim

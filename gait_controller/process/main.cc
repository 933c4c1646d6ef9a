// mrsim-gait: drives one robot of a running mrsim-sim with a sinusoid gait
// (docs/gait.md). Answers every state with joint targets, takes run-time
// changes from <prefix>_GAIT_<robot> and, with --keyboard, from the keys.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>

#include "gait_controller/gait_file.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/process/gait_node.h"
#include "gait_controller/process/joint_axes_spec.h"
#include "gait_controller/process/keyboard.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "sim_core/scenario_xml.h"

namespace {

constexpr const char* kKeyHelp =
    "keys: Up forward, Down backward, Left/Right turn (again: sharper), "
    "a/d sidewind left/right, r roll, space or s stop, +/- faster/slower, "
    "1-8 presets, h help, q quit";

mrsim::gait_command_t MotionCommand(const std::string& motion,
                                    double strength) {
  mrsim::gait_command_t c{};
  c.sender = "keyboard";
  c.motion = motion;
  c.strength = strength;
  return c;
}

// What a key asks for, given the current motion; nullopt for keys that do
// nothing. Sets *quit for q.
std::optional<mrsim::gait_command_t> KeyCommand(const mrsim::Key& key,
                                                const mrsim::GaitController* c,
                                                bool* quit) {
  using mrsim::KeyCode;
  using mrsim::Motion;
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
      return MotionCommand(mrsim::ToString(motion), s);
    }
    case 'q':
      *quit = true;
      return std::nullopt;
    default:
      break;
  }
  if (key.ch >= '1' && key.ch <= '9') {
    const size_t i = static_cast<size_t>(key.ch - '1');
    if (i < mrsim::GaitPresets().size()) {
      mrsim::gait_command_t g{};
      g.sender = "keyboard";
      g.gait = mrsim::GaitPresets()[i].name;
      return g;
    }
  }
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrsim-gait: drive one robot of mrsim-sim with a gait"};
  std::string robot;
  std::string lcm_url;
  std::string gait_spec = "forward";
  std::string scenario_path;
  std::string axes_text;
  std::string name;
  bool keyboard = false;
  mrsim::GaitNodeOptions options;
  app.add_option("--robot", robot, "Robot name (as in the scenario)")
      ->required();
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  app.add_option("--prefix", options.prefix, "Channel prefix")
      ->capture_default_str();
  app.add_option("--gait", gait_spec,
                 "Preset (" + mrsim::GaitPresetNames() +
                     "), gait file, or NAME.xml in MRSIM_GAIT_PATH/./gaits")
      ->capture_default_str();
  app.add_option("--scenario", scenario_path,
                 "Scenario file mrsim-sim runs (gives the joint axes; without "
                 "it or --axes, pitch-yaw is assumed)");
  app.add_option("--axes", axes_text,
                 "Joint axes instead of --scenario: pitch, yaw, pitch-yaw, "
                 "yaw-pitch or P/Y per joint");
  app.add_option("--rate", options.rate,
                 "Control rate in Hz of sim time (0: answer every state; "
                 "lockstep needs >= mrsim-sim's --rate)")
      ->capture_default_str();
  app.add_option("--name", name,
                 "Sender name (what mrsim-sim --controllers lists); default "
                 "gait-<robot>");
  app.add_flag("--keyboard", keyboard,
               "Steer from the keyboard (stdin must be a terminal)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  options.robot = robot;
  options.sender = name.empty() ? "gait-" + robot : name;
  mrsim::Gait initial;
  std::function<std::vector<mrsim::Axis>(int)> axes_for;
  try {
    initial = mrsim::ResolveGait(gait_spec);
    if (!scenario_path.empty() && !axes_text.empty()) {
      throw std::invalid_argument("give --scenario or --axes, not both");
    }
    if (!scenario_path.empty()) {
      const auto axes = mrsim::ScenarioJointAxes(scenario_path, robot);
      axes_for = [axes](int) { return axes; };
    } else if (!axes_text.empty()) {
      const mrsim::JointAxesSpec spec(axes_text);
      axes_for = [spec](int n) { return spec.Expand(n); };
    } else {
      // Robot states do not say which joint is pitch or yaw. Alternating
      // pitch-yaw is the common case (the case-study robot); say so loudly.
      std::cerr << "mrsim-gait: warning: no --scenario or --axes: assuming "
                   "alternating pitch-yaw joints, pitch first (give --scenario "
                   "FILE, the file mrsim-sim runs, to be sure)\n";
      const mrsim::JointAxesSpec spec("pitch-yaw");
      axes_for = [spec](int n) { return spec.Expand(n); };
    }
    if (!(options.rate >= 0))
      throw std::invalid_argument("--rate must be >= 0");
    if (keyboard && !isatty(STDIN_FILENO)) {
      throw std::invalid_argument("--keyboard: stdin is not a terminal");
    }
  } catch (const std::exception& e) {
    std::cerr << "mrsim-gait: " << e.what() << "\n";
    return 2;
  }

  try {
    mrsim::InstallStopHandlers();
    lcm::LCM lcm(lcm_url);
    if (!lcm.good()) {
      std::cerr << "mrsim-gait: cannot open LCM '" << lcm_url << "'\n";
      return 1;
    }
    mrsim::GaitNode node(lcm, options, axes_for, initial);
    std::unique_ptr<mrsim::RawKeyboard> keys;
    if (keyboard) {
      keys = std::make_unique<mrsim::RawKeyboard>();
      std::cerr << "mrsim-gait: " << kKeyHelp << "\r\n";
    }
    std::cerr << "mrsim-gait: robot " << robot << ", sender " << options.sender
              << ", gait " << initial.name << ", listening on "
              << mrsim::StateChannel(options.prefix, robot) << " and "
              << mrsim::GaitChannel(options.prefix, robot) << std::endl;
    bool quit = false;
    const char* eol = keyboard ? "\r\n" : "\n";
    while (!quit && !mrsim::StopRequested() && node.error().empty()) {
      mrsim::HandleFor(lcm, keys ? 20 : 100);
      while (keys) {
        const auto key = keys->Poll();
        if (!key) break;
        if (key->code == mrsim::KeyCode::kChar &&
            (key->ch == 'h' || key->ch == '?')) {
          std::cerr << "mrsim-gait: " << kKeyHelp << eol;
          continue;
        }
        if (auto c = KeyCommand(*key, node.controller(), &quit)) {
          node.Apply(*c, "keyboard");
        }
      }
      for (const std::string& line : node.TakeLog()) {
        std::cerr << "mrsim-gait: " << line << eol;
      }
    }
    keys.reset();  // the terminal back to normal before the summary
    const auto& n = node.counters();
    std::cerr << "mrsim-gait: " << robot << ": answered " << n.states_answered
              << " states (" << n.states_repeated << " repeated, "
              << n.states_skipped << " skipped), gait commands applied "
              << n.commands_applied << ", rejected " << n.commands_rejected
              << ", malformed messages " << n.messages_malformed << std::endl;
    if (!node.error().empty()) {
      std::cerr << "mrsim-gait: " << node.error() << "\n";
      return 2;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-gait: " << e.what() << "\n";
    return 1;
  }
}

#include "gait_controller/process/gait_command_line.h"

#include "gait_controller/gait_file.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/process/joint_axes_spec.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/version.h"

namespace mrsim {

void GaitCommandLine::AddFlags(CLI::App& app) {
  app.set_version_flag("--version", VersionLine("mrsim-gait"));
  app.add_option("--robot", robot, "Robot name (as in the scenario)")
      ->required();
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  AddAuthFlags(app, auth);
  app.add_option("--prefix", options.prefix, "Channel prefix")
      ->capture_default_str();
  app.add_option("--gait", gait_spec,
                 "Preset (" + GaitPresetNames() +
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
  app.add_option("--resume", resume,
                 "Continue the gait saved beside this simulator checkpoint "
                 "(CHECKPOINT.gait-ROBOT; use with mrsim-sim "
                 "--load-checkpoint CHECKPOINT)");
  app.add_flag(
      "--exit-with-sim", options.exit_with_sim,
      "Exit when the simulator stops (a --duration run ends, QUIT) or has "
      "been silent for 5 s, or when none was heard within 30 s");
  app.add_flag("--keyboard", keyboard,
               "Steer from the keyboard (stdin must be a terminal)");
}

void GaitCommandLine::Finish(bool stdin_is_terminal) {
  options.robot = robot;
  options.sender = name.empty() ? "gait-" + robot : name;
  try {
    initial = ResolveGait(gait_spec);
    if (!scenario_path.empty() && !axes_text.empty()) {
      throw std::invalid_argument("give --scenario or --axes, not both");
    }
    if (!scenario_path.empty()) {
      const auto axes = ScenarioJointAxes(scenario_path, robot);
      axes_for = [axes](int) { return axes; };
    } else {
      if (axes_text.empty()) {
        // Robot states do not say which joint is pitch or yaw. Alternating
        // pitch-yaw is the common case (the case-study robot); say so.
        warning =
            "warning: no --scenario or --axes: assuming alternating "
            "pitch-yaw joints, pitch first (give --scenario FILE, the file "
            "mrsim-sim runs, to be sure)";
      }
      const JointAxesSpec spec(axes_text.empty() ? "pitch-yaw" : axes_text);
      axes_for = [spec](int n) { return spec.Expand(n); };
    }
    if (!(options.rate >= 0)) {
      throw std::invalid_argument("--rate must be >= 0");
    }
    if (keyboard && !stdin_is_terminal) {
      throw std::invalid_argument("--keyboard: stdin is not a terminal");
    }
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
}

std::string GaitCommandLine::StartLine() const {
  return "mrsim-gait: robot " + options.robot + ", sender " + options.sender +
         ", gait " + initial.name + ", listening on " +
         StateChannel(options.prefix, options.robot) + " and " +
         GaitChannel(options.prefix, options.robot);
}

}  // namespace mrsim

#include "gait_controller/process/gait_command_line.h"

#include "gait_controller/gait_file.h"
#include "gait_controller/gait_presets.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/version.h"

namespace mrsim {

void GaitCommandLine::AddFlags(CLI::App& app) {
  app.set_version_flag("--version", VersionLine("mrsim-gait"));
  controller.AddFlags(
      app, {&options.prefix, &options.rate, &options.exit_with_sim},
      {"the joint axes",
       "Control rate in Hz of sim time (0: answer every state; lockstep "
       "needs >= mrsim-sim's --rate)",
       "Exit when the simulator stops (a --duration run ends, QUIT) or has "
       "been silent for 5 s, or when none was heard within 30 s"});
  app.add_option("--gait", gait_spec,
                 "Preset (" + GaitPresetNames() +
                     "), gait file, or NAME.xml in MRSIM_GAIT_PATH/./gaits")
      ->capture_default_str();
  app.add_option("--resume", resume,
                 "Continue the gait saved beside this simulator checkpoint "
                 "(CHECKPOINT.gait-ROBOT; use with mrsim-sim "
                 "--load-checkpoint CHECKPOINT)");
  app.add_flag("--keyboard", keyboard,
               "Steer from the keyboard (stdin must be a terminal)");
}

void GaitCommandLine::Finish(bool stdin_is_terminal) {
  try {
    initial = ResolveGait(gait_spec);
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
  controller.Finish(
      "warning: no --scenario or --axes: assuming alternating pitch-yaw "
      "joints, pitch first (give --scenario FILE, the file mrsim-sim runs, "
      "to be sure)");
  options.robot = controller.robot;
  options.sender = controller.sender;
  if (keyboard && !stdin_is_terminal) {
    throw UsageError("--keyboard: stdin is not a terminal");
  }
}

std::string GaitCommandLine::StartLine() const {
  return "mrsim-gait: robot " + options.robot + ", sender " + options.sender +
         ", gait " + initial.name + ", listening on " +
         StateChannel(options.prefix, options.robot) + " and " +
         GaitChannel(options.prefix, options.robot);
}

}  // namespace mrsim

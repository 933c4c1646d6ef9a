#include "studio/app/studio_flags.h"

#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"
#include "studio/design/selection_name.h"

namespace mrsim::studio {

void AddStudioFlags(CLI::App* cli, StudioFlags* f) {
  AppOptions& o = f->options;
  cli->add_option("SCENARIO", f->scenario, "Scenario file to open (or create)");
  CLI::Option* shot =
      cli->add_option("--screenshot", f->screenshot,
                      "Render the window once off-screen to this PNG and exit");
  cli->add_option("--select", f->select,
                  "Select this before the first frame: a robot or object "
                  "by name, [ROBOT ]module N, [ROBOT ]sensor_module N, "
                  "[ROBOT ]lock N, loose_frame N, loose_joint N, "
                  "loose_sensor_module N, terrain, settings or none");
  cli->add_option("--drag", f->drag,
                  "With --screenshot: press the left button at X0 Y0, drag "
                  "to X1 Y1 and take the picture while it is held (window "
                  "pixels, as --layout-dump writes them)")
      ->expected(4)
      ->allow_extra_args(false)  // SCENARIO may follow the four numbers
      ->needs(shot);
  cli->add_option("--width", o.width, "Window width")->capture_default_str();
  cli->add_option("--height", o.height, "Window height")->capture_default_str();
  cli->add_option("--ui-scale", o.ui_scale,
                  "Text and panel size (1: 15 px text; default: the "
                  "monitor's content scale)")
      ->check(CLI::Range(0.0f, 4.0f));
  cli->add_flag("--full-view", o.full_view,
                "Start with both side panels hidden: the 3-D view alone "
                "(F11 or the View menu brings them back)");
  cli->add_option("--layout-dump", o.layout_dump,
                  "Write widget rectangles and state here (for tests)");
  cli->add_option("--key-file", f->key_file,
                  "Sign the live session's messages, and those of the "
                  "processes it starts, with this key (default: "
                  "$MRSIM_KEY_FILE; docs/security.md)");
  cli->set_version_flag("--version", mrsim::VersionLine("mrsim-studio"));
}

AppOptions StartOptions(const StudioFlags& flags) {
  AppOptions options = flags.options;
  options.open_template = flags.scenario.empty();
  return options;
}

Design OpenDesign(const StudioFlags& flags) {
  Design design =
      flags.scenario.empty() ? Design() : Design::Open(flags.scenario);
  if (!flags.select.empty()) {
    try {
      design.Select(SelectionNamed(design.scenario(), flags.select));
    } catch (const DesignError& e) {
      throw UsageError(std::string("--select: ") + e.what());
    }
  }
  return design;
}

}  // namespace mrsim::studio
